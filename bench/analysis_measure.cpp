// The arch analysis measured against the real cases: detection on c1-c4 (both jaws)
// against their hand-placed landmarks (per landmark type: median and 95th-percentile distance,
// share of the given landmarks found), the relationships from detected landmarks against those
// from the given ones at the registered bite and against clinical.md's table, the orientation on
// the synthetic pair, and the thread CPU time of AnalyzeArch on each a-bite jaw.
//
//   occlude_analysis_measure [DATA_DIR] [--out DIR]
//
// DATA_DIR defaults to $OCCLUDE_DATA_DIR, else ../shared/data beside the source tree; without
// the cases it says so and exits 0. --out writes detection.csv, relationships.csv and, per case
// and jaw, <case>-<jaw>-landmarks.csv (detected landmarks, for drawing).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/arch_analysis.h"
#include "analysis/relationships.h"
#include "data_dir.h"
#include "occlude/angles.h"
#include "occlude/clock.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"

namespace fs = std::filesystem;
using namespace occlude;

namespace {

// clinical.md's table: overjet, overbite, midline, molar R, molar L, canine R, canine L (mm).
const std::map<std::string, std::vector<double>> kClinicalTable = {
    {"c1", {4.56, 5.44, 0.36, 0.19, -0.99, 3.31, 1.75}},
    {"c2", {6.51, 3.77, -0.87, 1.76, -1.12, 0.35, 2.24}},
    {"c3", {4.42, 4.92, -1.63, -0.98, 5.23, 2.04, 4.97}},
    {"c4", {1.25, 0.55, 0.89, -0.55, -1.10, 0.82, -0.70}}};
const char* kMeasureNames[7] = {"overjet", "overbite", "midline", "molar R",
                                "molar L", "canine R", "canine L"};

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

std::vector<std::optional<double>> Values(const analysis::Relationships& r) {
  return {r.overjet.mm,         r.overbite.mm,         r.midline_deviation.mm, r.molar[0].offset.mm,
          r.molar[1].offset.mm, r.canine[0].offset.mm, r.canine[1].offset.mm};
}

std::string Class(const std::optional<double>& v) {
  if (!v) return "-";
  analysis::Measure m;
  m.mm = v;
  return analysis::ToString(*analysis::Classify(m).occlusion_class);
}

// Issue 19's targets for a relationship from detected landmarks against the given ones.
constexpr double kIncisorTargetMm = 0.5;  // overjet, overbite, midline
constexpr double kSideTargetMm = 1.0;     // molar and canine, and the same class

// Whether measure i (kMeasureNames) detected `diff` mm off the given value meets its target.
bool WithinTarget(int i, const std::optional<double>& diff, const std::string& class_given,
                  const std::string& class_detected) {
  if (!diff) return false;
  if (i < 3) return std::abs(*diff) <= kIncisorTargetMm;
  return std::abs(*diff) <= kSideTargetMm && class_given == class_detected;
}

std::string Num(const std::optional<double>& v) {
  if (!v) return "missing";
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", *v);
  return b;
}

struct Errors {
  std::vector<double> d;  // distances of found landmarks, mm
  int given = 0;
};

void WriteLandmarks(const fs::path& file, const analysis::ArchAnalysis& a) {
  std::ofstream out(file);
  out << "jaw,tooth,type,x_mm,y_mm,z_mm,confidence\n";
  for (const auto& l : a.landmarks) {
    out << io::ToString(l.landmark.jaw) << "," << l.landmark.tooth_fdi << ","
        << io::ToString(l.landmark.type) << "," << l.landmark.p.x() << "," << l.landmark.p.y()
        << "," << l.landmark.p.z() << "," << l.confidence << "\n";
  }
}

// Detection errors of one jaw, per type, added to `errors`.
void Score(const analysis::ArchAnalysis& a, const std::vector<io::Landmark>& given,
           std::map<std::string, Errors>* errors) {
  for (const io::Landmark& g : given) {
    if (g.jaw != a.jaw) continue;
    Errors& e = (*errors)[io::ToString(g.type)];
    ++e.given;
    if (const analysis::ArchLandmark* d = a.Find(g.tooth_fdi, g.type)) {
      e.d.push_back((d->landmark.p - g.p).norm());
    }
  }
}

void PrintDetection(const std::string& title, const std::map<std::string, Errors>& errors,
                    std::ofstream* csv) {
  std::printf("\n%s\n| type | given | found | median mm | p95 mm |\n|---|---|---|---|---|\n",
              title.c_str());
  for (const auto& [type, e] : errors) {
    std::printf("| %s | %d | %zu (%.0f %%) | %.2f | %.2f |\n", type.c_str(), e.given, e.d.size(),
                100.0 * static_cast<double>(e.d.size()) / std::max(1, e.given),
                Percentile(e.d, 0.5), Percentile(e.d, 0.95));
    if (csv) {
      *csv << title << "," << type << "," << e.given << "," << e.d.size() << ","
           << Percentile(e.d, 0.5) << "," << Percentile(e.d, 0.95) << "\n";
    }
  }
}

struct CaseResult {
  std::map<std::string, Errors> errors;
  std::vector<std::optional<double>> given, detected;
};

CaseResult MeasureCase(const fs::path& dir, const std::string& name, const fs::path* out) {
  CaseResult res;
  const std::vector<io::Landmark> given = io::ReadLandmarkFile(dir / "landmarks.csv");
  std::vector<io::Landmark> given_upper, given_lower;
  for (const auto& l : given) (l.jaw == io::Jaw::kUpper ? given_upper : given_lower).push_back(l);
  analysis::ArchAnalysis jaws[2];
  for (const io::Jaw jaw : {io::Jaw::kLower, io::Jaw::kUpper}) {
    const io::TriangleMesh mesh = io::LoadMesh(dir / (std::string(io::ToString(jaw)) + ".stl"));
    analysis::ArchAnalysis& a = jaws[jaw == io::Jaw::kUpper ? 1 : 0];
    a = analysis::AnalyzeArch(mesh, jaw);
    std::vector<double> confidence;
    for (const analysis::ArchTooth& t : a.teeth) confidence.push_back(t.confidence);
    std::printf("%s %s: %s, %zu teeth (confidence min %.2f, median %.2f), %zu landmarks%s\n",
                name.c_str(), io::ToString(jaw), a.ok() ? "ok" : a.error.c_str(), a.teeth.size(),
                Percentile(confidence, 0.0), Percentile(confidence, 0.5), a.landmarks.size(),
                a.notes.empty() ? "" : ("; " + a.notes.front()).c_str());
    Score(a, given, &res.errors);
    if (out) WriteLandmarks(*out / (name + "-" + io::ToString(jaw) + "-landmarks.csv"), a);
  }
  const Eigen::Isometry3d bite = Eigen::Isometry3d::Identity();  // both meshes in one frame
  res.given = Values(analysis::ComputeRelationships(given_upper, given_lower, bite, std::nullopt));
  res.detected = Values(
      analysis::ComputeRelationships(jaws[1].Points(), jaws[0].Points(), bite, jaws[0].frame));
  return res;
}

void PrintRelationships(const std::map<std::string, CaseResult>& cases, std::ofstream* csv) {
  std::printf(
      "\n| case | measure | clinical.md | given | detected | detected - given | class "
      "given / detected |\n|---|---|---|---|---|---|---|\n");
  double worst_given = 0.0;
  int within = 0, rows = 0;
  for (const auto& [name, r] : cases) {
    const std::vector<double>& table = kClinicalTable.at(name);
    for (int i = 0; i < 7; ++i) {
      const auto& g = r.given[static_cast<std::size_t>(i)];
      const auto& d = r.detected[static_cast<std::size_t>(i)];
      if (g) worst_given = std::max(worst_given, std::abs(*g - table[static_cast<std::size_t>(i)]));
      std::optional<double> diff;
      if (g && d) diff = *d - *g;
      const std::string cls = i >= 3 ? Class(g) + " / " + Class(d) : "";
      ++rows;
      within += WithinTarget(i, diff, Class(g), Class(d));
      std::printf("| %s | %s | %.2f | %s | %s | %s | %s |\n", name.c_str(), kMeasureNames[i],
                  table[static_cast<std::size_t>(i)], Num(g).c_str(), Num(d).c_str(),
                  Num(diff).c_str(), cls.c_str());
      if (csv) {
        *csv << name << "," << kMeasureNames[i] << "," << table[static_cast<std::size_t>(i)] << ","
             << Num(g) << "," << Num(d) << "," << Num(diff) << "\n";
      }
    }
  }
  std::printf(
      "\nrows within target (overjet, overbite, midline within %.1f mm; molar and canine within "
      "%.1f mm and the same class): %d of %d\n",
      kIncisorTargetMm, kSideTargetMm, within, rows);
  std::printf(
      "\ngiven landmarks against clinical.md's table: largest difference %.4f mm (%s "
      "0.05 mm)\n",
      worst_given, worst_given <= 0.05 ? "within" : "NOT within");
}

// Thread CPU seconds of AnalyzeArch: the smallest and the median of `reps` runs.
void TimeJaw(const std::string& label, const io::TriangleMesh& mesh, io::Jaw jaw, int reps) {
  std::vector<double> t;
  analysis::ArchAnalysis a;
  for (int r = 0; r < reps; ++r) {
    const double t0 = occlude::ThreadCpuSeconds();
    a = analysis::AnalyzeArch(mesh, jaw);
    t.push_back(occlude::ThreadCpuSeconds() - t0);
  }
  std::printf("| %s | %zu | %zu teeth (%s) | %.3f | %.3f |\n", label.c_str(), mesh.num_triangles(),
              a.teeth.size(), a.teeth.empty() ? "-" : analysis::ToString(a.teeth.front().source),
              *std::min_element(t.begin(), t.end()), Percentile(t, 0.5));
}

void TimeABite(const fs::path& dir) {
  if (!fs::exists(dir / "lower.stl")) return;
  std::printf(
      "\n| a-bite jaw | triangles | found | CPU s (min) | CPU s (median of 5) |\n"
      "|---|---|---|---|---|\n");
  for (const io::Jaw jaw : {io::Jaw::kLower, io::Jaw::kUpper}) {
    const std::string j = io::ToString(jaw);
    TimeJaw(j + ".stl", io::LoadMesh(dir / (j + ".stl")), jaw, 5);
    std::vector<fs::path> parts;
    for (const auto& e : fs::directory_iterator(dir / "teeth")) {
      const int n = io::ToothNumberFromFileName(e.path().stem().string());
      const bool mine = jaw == io::Jaw::kUpper ? (n >= 1 && n <= 16) : n >= 17;
      const bool gum =
          e.path().stem() == (jaw == io::Jaw::kUpper ? "Tooth_UpperJaw" : "Tooth_LowerJaw");
      if (mine || gum) parts.push_back(e.path());
    }
    std::sort(parts.begin(), parts.end());
    TimeJaw("teeth/ " + j + " parts", io::LoadJawParts(parts), jaw, 5);
  }
}

// The orientation of one synthetic jaw's detected frame against the design (L: x left, y up,
// z anterior; the upper's occlusal axis points down).
void PrintSyntheticFrame(const analysis::ArchAnalysis& a) {
  const Eigen::Vector3d up = a.jaw == io::Jaw::kLower ? Eigen::Vector3d::UnitY()
                                                      : Eigen::Vector3d(-Eigen::Vector3d::UnitY());
  const auto deg = [](const Eigen::Vector3d& a_, const Eigen::Vector3d& b) {
    return DegreesFromRadians(std::acos(std::clamp(a_.dot(b), -1.0, 1.0)));
  };
  std::printf("| %s | %zu | %zu | %.2f | %.2f | %.2f |\n", io::ToString(a.jaw), a.teeth.size(),
              a.landmarks.size(), deg(a.frame.occlusal_J, up),
              deg(a.frame.anterior_J, Eigen::Vector3d::UnitZ()),
              deg(a.frame.lateral_J, Eigen::Vector3d::UnitX()));
}

// The synthetic pair (seed 1, 20,000 triangles): the detected frames, the detection against the
// generator's landmarks, and the relationships from detected and from its landmarks against the
// designed ones.
void Synthetic(const fs::path* out) {
  const io::SyntheticJawPair pair = io::MakeSyntheticJawPair({});
  std::printf(
      "\n| synthetic jaw | teeth | landmarks | occlusal err deg | anterior err deg | "
      "left err deg |\n|---|---|---|---|---|---|\n");
  analysis::ArchAnalysis jaws[2];
  std::map<std::string, Errors> errors;
  std::vector<io::Landmark> given[2];
  for (const io::Jaw jaw : {io::Jaw::kLower, io::Jaw::kUpper}) {
    const int j = jaw == io::Jaw::kUpper ? 1 : 0;
    jaws[j] = analysis::AnalyzeArch(j ? pair.upper_U : pair.lower_L, jaw);
    PrintSyntheticFrame(jaws[j]);
    Score(jaws[j], pair.landmarks, &errors);
    if (out)
      WriteLandmarks(*out / (std::string("synthetic-") + io::ToString(jaw) + "-landmarks.csv"),
                     jaws[j]);
  }
  for (const io::Landmark& l : pair.landmarks) given[l.jaw == io::Jaw::kUpper ? 1 : 0].push_back(l);
  if (out) {
    std::ofstream csv(*out / "synthetic-given-landmarks.csv");
    csv << "jaw,tooth,type,x_mm,y_mm,z_mm\n";
    for (const io::Landmark& l : pair.landmarks) {
      csv << io::ToString(l.jaw) << "," << l.tooth_fdi << "," << io::ToString(l.type) << ","
          << l.p.x() << "," << l.p.y() << "," << l.p.z() << "\n";
    }
  }
  PrintDetection("synthetic", errors, nullptr);
  const io::SyntheticRelationships& d = pair.relationships;
  const std::vector<double> designed = {d.overjet_mm,     d.overbite_mm,   d.midline_deviation_mm,
                                        d.molar_mm.right, d.molar_mm.left, d.canine_mm.right,
                                        d.canine_mm.left};
  const auto from_given =
      Values(analysis::ComputeRelationships(given[1], given[0], pair.X_LU, std::nullopt));
  const auto detected = Values(
      analysis::ComputeRelationships(jaws[1].Points(), jaws[0].Points(), pair.X_LU, jaws[0].frame));
  std::printf(
      "\n| synthetic | designed | from its landmarks | detected | detected - designed | class "
      "designed / detected |\n|---|---|---|---|---|---|\n");
  int within = 0;
  for (std::size_t i = 0; i < 7; ++i) {
    std::optional<double> diff;
    if (detected[i]) diff = *detected[i] - designed[i];
    const std::string cls = i >= 3 ? Class(designed[i]) + " / " + Class(detected[i]) : "";
    within += WithinTarget(static_cast<int>(i), diff, Class(designed[i]), Class(detected[i]));
    std::printf("| %s | %.2f | %s | %s | %s | %s |\n", kMeasureNames[i], designed[i],
                Num(from_given[i]).c_str(), Num(detected[i]).c_str(), Num(diff).c_str(),
                cls.c_str());
  }
  std::printf("\nsynthetic rows within target: %d of 7\n", within);
}

}  // namespace

int main(int argc, char** argv) {
  fs::path data = occlude::bench::DataDir();
  std::optional<fs::path> out;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else {
      data = arg;
    }
  }
  if (!fs::exists(data / "cases" / "c1-ios-decimated")) {
    std::printf("skipped: no real cases under %s (pass DATA_DIR or set OCCLUDE_DATA_DIR)\n",
                data.c_str());
    return 0;
  }
  std::ofstream detection_csv, relationships_csv;
  if (out) {
    fs::create_directories(*out);
    detection_csv.open(*out / "detection.csv");
    detection_csv << "case,type,given,found,median_mm,p95_mm\n";
    relationships_csv.open(*out / "relationships.csv");
    relationships_csv << "case,measure,clinical_md,given,detected,detected_minus_given\n";
  }
  std::map<std::string, CaseResult> cases;
  std::map<std::string, Errors> all;
  for (const std::string name : {"c1", "c2", "c3", "c4"}) {
    const fs::path dir = data / "cases" / (name + "-ios-decimated");
    cases[name] = MeasureCase(dir, name, out ? &*out : nullptr);
    for (const auto& [type, e] : cases[name].errors) {
      all[type].given += e.given;
      all[type].d.insert(all[type].d.end(), e.d.begin(), e.d.end());
    }
  }
  for (const auto& [name, r] : cases) {
    PrintDetection(name, r.errors, out ? &detection_csv : nullptr);
  }
  PrintDetection("all", all, out ? &detection_csv : nullptr);
  PrintRelationships(cases, out ? &relationships_csv : nullptr);
  Synthetic(out ? &*out : nullptr);
  TimeABite(data / "cases" / "a-bite-3shape");
  return 0;
}
