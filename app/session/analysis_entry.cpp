// The arch analysis cache entry (analysis_entry.h): a JSON array per structure, enums as their
// numbers (range-checked when read), doubles as nlohmann writes them (the shortest form that
// reads back as the same double; a non-finite one would be written as null, which fails to read
// and so is made again, never taken wrongly).
#include "session/analysis_entry.h"

#include <nlohmann/json.hpp>

#include "occlude/io/content_hash.h"

namespace occlude::app {
namespace {

using nlohmann::json;

constexpr std::uint32_t kEncodingVersion = 1;

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d VecOf(const json& j) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error("a point is not 3 numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

// An enum stored as its number, checked to be in [0, count).
template <typename E>
E EnumOf(const json& j, int count, const char* what) {
  const int v = j.get<int>();
  if (v < 0 || v >= count) throw std::runtime_error(std::string("unknown ") + what);
  return static_cast<E>(v);
}

}  // namespace

std::uint64_t ArchAnalysisKey(const io::TriangleMesh& mesh, io::Jaw jaw,
                              const analysis::ArchAnalysisOptions& options) {
  io::Hasher64 h;
  h.AddString("occlude arch analysis");
  h.AddValue(kEncodingVersion);
  h.AddString(analysis::ArchAnalysisCodeVersion());
  h.AddValue(static_cast<int>(jaw));
  h.AddValue(options.grid_mm);
  h.AddValue(options.curve_step_mm);
  h.AddValue(options.crown_depth_mm);
  h.AddValue(io::MeshContentHash(mesh));
  return h.Finish();
}

std::string EncodeArchAnalysis(const analysis::ArchAnalysis& a) {
  json curve = json::array();
  for (const Eigen::Vector3d& p : a.arch_curve_J) curve.push_back(Vec(p));
  json teeth = json::array();
  for (const analysis::ArchTooth& t : a.teeth) {
    teeth.push_back({t.fdi, Vec(t.centre_J), static_cast<int>(t.source), t.mesial_mm, t.distal_mm,
                     t.confidence});
  }
  json landmarks = json::array();
  for (const analysis::ArchLandmark& l : a.landmarks) {
    landmarks.push_back({static_cast<int>(l.landmark.jaw), l.landmark.tooth_fdi,
                         static_cast<int>(l.landmark.type), Vec(l.landmark.p),
                         static_cast<int>(l.source), l.confidence, l.method});
  }
  const json j = {{"jaw", static_cast<int>(a.jaw)},
                  {"error", a.error},
                  {"frame",
                   {Vec(a.frame.origin_J), Vec(a.frame.lateral_J), Vec(a.frame.anterior_J),
                    Vec(a.frame.occlusal_J)}},
                  {"curve", curve},
                  {"midline", Vec(a.midline_J)},
                  {"teeth", teeth},
                  {"landmarks", landmarks},
                  {"notes", a.notes}};
  return j.dump();
}

analysis::ArchAnalysis DecodeArchAnalysis(std::string_view bytes) {
  try {
    const json j = json::parse(bytes);
    analysis::ArchAnalysis a;
    a.jaw = EnumOf<io::Jaw>(j.at("jaw"), 2, "jaw");
    a.error = j.at("error").get<std::string>();
    const json& frame = j.at("frame");
    if (!frame.is_array() || frame.size() != 4) throw std::runtime_error("frame is not 4 axes");
    a.frame = {VecOf(frame[0]), VecOf(frame[1]), VecOf(frame[2]), VecOf(frame[3])};
    for (const json& p : j.at("curve")) a.arch_curve_J.push_back(VecOf(p));
    a.midline_J = VecOf(j.at("midline"));
    for (const json& t : j.at("teeth")) {
      if (!t.is_array() || t.size() != 6) throw std::runtime_error("a tooth is not 6 fields");
      a.teeth.push_back({t[0].get<int>(), VecOf(t[1]),
                         EnumOf<analysis::ToothSource>(t[2], 3, "tooth source"), t[3].get<double>(),
                         t[4].get<double>(), t[5].get<double>()});
    }
    for (const json& l : j.at("landmarks")) {
      if (!l.is_array() || l.size() != 7) throw std::runtime_error("a landmark is not 7 fields");
      analysis::ArchLandmark m;
      m.landmark.jaw = EnumOf<io::Jaw>(l[0], 2, "jaw");
      m.landmark.tooth_fdi = l[1].get<int>();
      m.landmark.type = EnumOf<io::LandmarkType>(l[2], io::kNumLandmarkTypes, "landmark type");
      m.landmark.p = VecOf(l[3]);
      m.source = EnumOf<analysis::LandmarkSource>(l[4], 2, "landmark source");
      m.confidence = l[5].get<double>();
      m.method = l[6].get<std::string>();
      a.landmarks.push_back(std::move(m));
    }
    a.notes = j.at("notes").get<std::vector<std::string>>();
    return a;
  } catch (const std::exception& e) {  // json's errors and the checks' above
    throw std::runtime_error(std::string("malformed arch analysis: ") + e.what());
  }
}

}  // namespace occlude::app
