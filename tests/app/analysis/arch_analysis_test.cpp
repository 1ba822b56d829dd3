// AnalyzeArch on the synthetic pair (teeth from its numbered parts, and segmented when the
// parts are merged into one surface), on rotated copies (the frame and landmarks move with the
// mesh), against the pair's designed landmarks and relationships, on meshes without teeth, and on
// the c-cases (skipped without ../shared/data).
#include "analysis/arch_analysis.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../common/test_common.h"
#include "analysis/relationships.h"
#include "occlude/angles.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"

namespace occlude::analysis {
namespace {

using io::Jaw;
using io::LandmarkType;

// Detection works on a 0.2 mm height map: a rigid motion moves what it finds by up to a few
// cells (a different raster of the same surface).
constexpr double kMovedLandmarkMm = 0.6;
constexpr double kMovedFrameDeg = 2.0;
constexpr double kMovedIncisalMm = 1.0;
// On a real scan this share of the landmarks may stray farther (c4 lower: 8-11 of 90 measured).
constexpr double kCaseStrayShare = 0.15;  // the middle of a ridge sloping by a few tenths
// Targets on the synthetic pair (docs/results/analysis/README.md), with the medians measured by
// occlude_analysis_measure (docs/results/analysis/README.md).
constexpr double kSyntheticIncisalMedianMm = 0.5;
constexpr double kSyntheticCuspMedianMm = 1.0;
constexpr double kFrameDeg = 3.0;
// A segmented tooth's boundaries along the arch this close to its part's (seed 1: <= 0.5 mm).
constexpr double kSegmentedBoundaryMm = 0.75;
constexpr double kCuspBelowTopMm = 0.1;
// A c-case incisal edge no farther than this from the hand-placed one (worst measured 2.5 mm).
constexpr double kCaseIncisalMm = 3.0;

const io::SyntheticJawPair& Pair() {
  static const io::SyntheticJawPair pair = io::MakeSyntheticJawPair({});
  return pair;
}

double Deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return DegreesFromRadians(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

std::vector<int> Fdis(const ArchAnalysis& a) {
  std::vector<int> fdi;
  for (const ArchTooth& t : a.teeth) fdi.push_back(t.fdi);
  return fdi;
}

// FDI numbers of a full arch of 14, patient's right to left.
std::vector<int> FullArch(Jaw jaw) {
  std::vector<int> fdi;
  const int right = jaw == Jaw::kUpper ? 1 : 4, left = jaw == Jaw::kUpper ? 2 : 3;
  for (int p = 7; p >= 1; --p) fdi.push_back(10 * right + p);
  for (int p = 1; p <= 7; ++p) fdi.push_back(10 * left + p);
  return fdi;
}

// The design's arch frame of a jaw in its own frame (L or U): x left, z anterior, and occlusal
// +y for the lower, -y for the upper.
ArchFrame DesignFrame(Jaw jaw) {
  ArchFrame f;
  f.lateral_J = Eigen::Vector3d::UnitX();
  f.anterior_J = Eigen::Vector3d::UnitZ();
  f.occlusal_J = Eigen::Vector3d::UnitY();
  if (jaw == Jaw::kUpper) f.occlusal_J = -f.occlusal_J;
  return f;
}

void ExpectFrameNear(const ArchFrame& got, const ArchFrame& want, double deg) {
  EXPECT_LT(Deg(got.lateral_J, want.lateral_J), deg);
  EXPECT_LT(Deg(got.anterior_J, want.anterior_J), deg);
  EXPECT_LT(Deg(got.occlusal_J, want.occlusal_J), deg);
  EXPECT_NEAR(got.lateral_J.cross(got.anterior_J).dot(got.occlusal_J),
              want.lateral_J.cross(want.anterior_J).dot(want.occlusal_J), 1e-6);
}

// The landmarks that are maxima of the occlusal surface (cusp tips).
bool IsPeak(LandmarkType t) {
  return t == LandmarkType::kCuspTip || t == LandmarkType::kBuccalCusp ||
         t == LandmarkType::kLingualCusp || t == LandmarkType::kMbCusp ||
         t == LandmarkType::kMiddleBuccalCusp || t == LandmarkType::kDbCusp ||
         t == LandmarkType::kMlCusp || t == LandmarkType::kDlCusp;
}

class SyntheticJaw : public ::testing::TestWithParam<Jaw> {
 protected:
  const io::TriangleMesh& Mesh() const {
    return GetParam() == Jaw::kUpper ? Pair().upper_U : Pair().lower_L;
  }
};

TEST_P(SyntheticJaw, TeethComeFromTheNumberedPartsInArchOrder) {
  const ArchAnalysis a = AnalyzeArch(Mesh(), GetParam());
  ASSERT_TRUE(a.ok()) << a.error;
  EXPECT_EQ(Fdis(a), FullArch(GetParam()));
  for (const ArchTooth& t : a.teeth) {
    EXPECT_EQ(t.source, ToothSource::kParts);
    EXPECT_GE(t.confidence, 0.0);
    EXPECT_LE(t.confidence, 1.0);
    // The centre lies on its own side of the midline (x left).
    EXPECT_EQ(t.centre_J.x() > 0.0, io::IsLeftSide(t.fdi)) << t.fdi;
  }
  ExpectFrameNear(a.frame, DesignFrame(GetParam()), kFrameDeg);
  EXPECT_LT(std::abs(a.midline_J.x()), 0.5);
  ASSERT_GE(a.arch_curve_J.size(), 2u);
  EXPECT_LT(a.arch_curve_J.front().x(), 0.0);  // right to left
  EXPECT_GT(a.arch_curve_J.back().x(), 0.0);
}

TEST_P(SyntheticJaw, LandmarksLieOnTheirToothWithConfidenceAndMethod) {
  const ArchAnalysis a = AnalyzeArch(Mesh(), GetParam());
  ASSERT_TRUE(a.ok()) << a.error;
  std::map<int, Eigen::Vector3d> centre;
  for (const ArchTooth& t : a.teeth) centre[t.fdi] = t.centre_J;
  for (const ArchLandmark& l : a.landmarks) {
    EXPECT_EQ(l.landmark.jaw, GetParam());
    ASSERT_TRUE(centre.count(l.landmark.tooth_fdi)) << l.landmark.tooth_fdi;
    EXPECT_LT((l.landmark.p - centre[l.landmark.tooth_fdi]).norm(), 8.0);
    EXPECT_GT(l.confidence, 0.0);
    EXPECT_LE(l.confidence, 1.0);
    EXPECT_EQ(l.source, LandmarkSource::kDetected);
    EXPECT_FALSE(l.method.empty());
    EXPECT_EQ(a.Find(l.landmark.tooth_fdi, l.landmark.type), &l);
  }
}

// A cusp tip is where its tooth's surface is highest nearby: no vertex of the tooth's part
// within 1 mm across the occlusal axis rises more than a little above it (the tip is the middle
// of its plateau, the cells within 0.05 mm of the peak).
TEST_P(SyntheticJaw, CuspLandmarksAreLocalMaximaOfTheirPart) {
  const ArchAnalysis a = AnalyzeArch(Mesh(), GetParam());
  ASSERT_TRUE(a.ok()) << a.error;
  const io::TriangleMesh& mesh = Mesh();
  const Eigen::Vector3d up = a.frame.occlusal_J;
  int checked = 0;
  for (const ArchLandmark& l : a.landmarks) {
    const LandmarkType t = l.landmark.type;
    if (!IsPeak(t)) continue;
    const int universal = io::UniversalFromFdi(l.landmark.tooth_fdi);
    double highest = -1e9;
    for (std::size_t f = 0; f < mesh.num_triangles(); ++f) {
      if (mesh.parts[static_cast<std::size_t>(mesh.triangle_part[f])].tooth_number != universal)
        continue;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d d = mesh.corner(f, k) - l.landmark.p;
        if ((d - d.dot(up) * up).norm() <= 1.0) highest = std::max(highest, d.dot(up));
      }
    }
    EXPECT_LT(highest, kCuspBelowTopMm) << l.landmark.tooth_fdi << " " << io::ToString(t);
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// Against the generator's designed landmarks: incisal edges and cusp tips near them.
TEST_P(SyntheticJaw, DetectionNearTheDesignedLandmarks) {
  const ArchAnalysis a = AnalyzeArch(Mesh(), GetParam());
  ASSERT_TRUE(a.ok()) << a.error;
  std::vector<double> incisal, cusps;
  int designed_cusps = 0;
  for (const io::Landmark& g : Pair().landmarks) {
    if (g.jaw != GetParam()) continue;
    const bool is_incisal = g.type == LandmarkType::kIncisalEdge;
    const bool is_cusp = g.type == LandmarkType::kCuspTip || g.type == LandmarkType::kMbCusp ||
                         g.type == LandmarkType::kBuccalCusp ||
                         g.type == LandmarkType::kLingualCusp || g.type == LandmarkType::kDlCusp;
    if (!is_incisal && !is_cusp) continue;
    designed_cusps += is_cusp;
    const ArchLandmark* d = a.Find(g.tooth_fdi, g.type);
    if (is_incisal) {
      ASSERT_NE(d, nullptr) << g.tooth_fdi;
    }
    if (d) (is_incisal ? incisal : cusps).push_back((d->landmark.p - g.p).norm());
  }
  ASSERT_EQ(incisal.size(), 4u);
  EXPECT_GE(4 * cusps.size(), 3u * static_cast<std::size_t>(designed_cusps));
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  EXPECT_LT(median(incisal), kSyntheticIncisalMedianMm);
  EXPECT_LT(median(cusps), kSyntheticCuspMedianMm);
}

// Analyses `mesh` in a random position A and after three more random motions: the teeth and the
// frame move with the mesh, and so do the landmarks (only the peaks and incisal edges when
// `peaks_only`): each within kMovedLandmarkMm (kMovedIncisalMm for an incisal edge) unless
// `stray_share` allows that share of them to stray (a boundary between regions that moves by a
// cell makes a rule pick another peak or contact).
void ExpectDetectionMovesWithMesh(const io::TriangleMesh& mesh, Jaw jaw, bool peaks_only,
                                  double stray_share) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random_motion = [&] {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    return Eigen::Isometry3d(Eigen::Translation3d(30 * u(rng), 30 * u(rng), 30 * u(rng)) *
                             Eigen::AngleAxisd(kPi * u(rng), axis));
  };
  const Eigen::Isometry3d X_AJ = random_motion();
  const ArchAnalysis a0 = AnalyzeArch(mesh.Transformed(X_AJ), jaw);
  ASSERT_TRUE(a0.ok()) << a0.error;
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::Isometry3d X_GA = random_motion();
    const ArchAnalysis a = AnalyzeArch(mesh.Transformed(X_GA * X_AJ), jaw);
    ASSERT_TRUE(a.ok()) << a.error;
    EXPECT_EQ(Fdis(a), Fdis(a0));
    ArchFrame moved = a0.frame;
    moved.lateral_J = X_GA.linear() * a0.frame.lateral_J;
    moved.anterior_J = X_GA.linear() * a0.frame.anterior_J;
    moved.occlusal_J = X_GA.linear() * a0.frame.occlusal_J;
    ExpectFrameNear(a.frame, moved, kMovedFrameDeg);
    int compared = 0, matched = 0, strays = 0;
    std::string stray_names;
    for (const ArchLandmark& l0 : a0.landmarks) {
      const LandmarkType t = l0.landmark.type;
      const bool incisal = t == LandmarkType::kIncisalEdge;
      if (peaks_only && !IsPeak(t) && !incisal) continue;
      ++compared;
      const ArchLandmark* l = a.Find(l0.landmark.tooth_fdi, t);
      if (!l) continue;
      ++matched;
      const double d = (l->landmark.p - X_GA * l0.landmark.p).norm();
      if (d >= (incisal ? kMovedIncisalMm : kMovedLandmarkMm)) {
        ++strays;
        stray_names += " " + std::to_string(l0.landmark.tooth_fdi) + " " + io::ToString(t);
      }
    }
    EXPECT_GE(10 * matched, 9 * compared);
    EXPECT_LE(strays, stray_share * compared) << trial << ":" << stray_names;
  }
}

// On the synthetic pair only the peaks: its flat floors, vertical walls and the faces its
// neighbouring crowns share make the lowest, outermost and closest points ties that a raster
// of another orientation breaks elsewhere (the real scans below check every landmark).
TEST_P(SyntheticJaw, DetectionMovesWithARigidMotion) {
  ExpectDetectionMovesWithMesh(Mesh(), GetParam(), true, 0.0);
}

TEST(ArchAnalysis, CaseDetectionMovesWithARigidMotion) {
  OCCLUDE_REQUIRE_CASE(dir, "c4-ios-decimated");
  ExpectDetectionMovesWithMesh(io::LoadMesh(dir / "lower.stl"), Jaw::kLower, false,
                               kCaseStrayShare);
}

// The parts merged into one surface: the teeth are segmented along the arch, numbered as the
// parts were, their boundaries along the arch near the parts'.
TEST_P(SyntheticJaw, SegmentsTheMergedSurface) {
  io::TriangleMesh merged = Mesh();
  merged.parts = {io::MeshPart{"jaw", 0}};
  std::fill(merged.triangle_part.begin(), merged.triangle_part.end(), 0);
  const ArchAnalysis parts = AnalyzeArch(Mesh(), GetParam());
  const ArchAnalysis a = AnalyzeArch(merged, GetParam());
  ASSERT_TRUE(a.ok()) << a.error;
  EXPECT_EQ(Fdis(a), FullArch(GetParam()));
  for (std::size_t i = 0; i < a.teeth.size() && i < parts.teeth.size(); ++i) {
    EXPECT_EQ(a.teeth[i].source, ToothSource::kSegmented);
    // Boundaries between crowns agree; a last molar's outer end is where its crown fades.
    EXPECT_NEAR(a.teeth[i].mesial_mm, parts.teeth[i].mesial_mm, kSegmentedBoundaryMm)
        << a.teeth[i].fdi;
    if (io::ToothPosition(a.teeth[i].fdi) < 7) {
      EXPECT_NEAR(a.teeth[i].distal_mm, parts.teeth[i].distal_mm, kSegmentedBoundaryMm)
          << a.teeth[i].fdi;
    }
  }
  ExpectFrameNear(a.frame, DesignFrame(GetParam()), kFrameDeg);
}

INSTANTIATE_TEST_SUITE_P(BothJaws, SyntheticJaw, ::testing::Values(Jaw::kLower, Jaw::kUpper),
                         [](const ::testing::TestParamInfo<Jaw>& param) {
                           return std::string(io::ToString(param.param));
                         });

// The synthetic bite's relationships from detected landmarks: overjet, overbite and midline
// within 0.5 mm of the design, molars within 1.0 mm and the same class (the analysis targets).
TEST(ArchAnalysis, SyntheticRelationshipsFromDetectedLandmarks) {
  const io::SyntheticJawPair& pair = Pair();
  const ArchAnalysis lower = AnalyzeArch(pair.lower_L, Jaw::kLower);
  const ArchAnalysis upper = AnalyzeArch(pair.upper_U, Jaw::kUpper);
  const Relationships r =
      ComputeRelationships(upper.Points(), lower.Points(), pair.X_LU, lower.frame);
  const io::SyntheticRelationships& d = pair.relationships;
  ASSERT_TRUE(r.overjet.mm && r.overbite.mm && r.midline_deviation.mm);
  EXPECT_NEAR(*r.overjet.mm, d.overjet_mm, 0.5);
  EXPECT_NEAR(*r.overbite.mm, d.overbite_mm, 0.5);
  EXPECT_NEAR(*r.midline_deviation.mm, d.midline_deviation_mm, 0.5);
  for (const auto& [side, want] : {std::pair{0, d.molar_mm.right}, std::pair{1, d.molar_mm.left}}) {
    ASSERT_TRUE(r.molar[side].offset.mm) << r.molar[side].offset.note;
    EXPECT_NEAR(*r.molar[side].offset.mm, want, 1.0);
    EXPECT_EQ(r.molar[side].occlusion_class, OcclusionClass::kI);
  }
}

TEST(ArchAnalysis, GivenLandmarksOverrideDetection) {
  ArchAnalysis a = AnalyzeArch(Pair().lower_L, Jaw::kLower);
  ASSERT_TRUE(a.ok()) << a.error;
  const std::size_t before = a.landmarks.size();
  const ArchLandmark* detected = a.Find(41, LandmarkType::kIncisalEdge);
  ASSERT_NE(detected, nullptr);
  io::Landmark moved = detected->landmark;
  moved.p += Eigen::Vector3d(0.3, -0.2, 0.1);
  io::Landmark upper{Jaw::kUpper, 11, LandmarkType::kIncisalEdge, Eigen::Vector3d(1, 2, 3)};
  std::vector<io::Landmark> given = {moved, upper};
  const bool had_fossa = a.Find(36, LandmarkType::kCentralFossa) != nullptr;
  a.landmarks.erase(std::remove_if(a.landmarks.begin(), a.landmarks.end(),
                                   [](const ArchLandmark& l) {
                                     return l.landmark.tooth_fdi == 36 &&
                                            l.landmark.type == LandmarkType::kCentralFossa;
                                   }),
                    a.landmarks.end());
  given.push_back({Jaw::kLower, 36, LandmarkType::kCentralFossa, Eigen::Vector3d(-20, 0, 5)});
  ApplyGivenLandmarks(given, &a);
  EXPECT_EQ(a.landmarks.size(), before - (had_fossa ? 1 : 0) + 1);
  const ArchLandmark* l = a.Find(41, LandmarkType::kIncisalEdge);
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->source, LandmarkSource::kGiven);
  EXPECT_EQ(l->confidence, 1.0);
  EXPECT_EQ(l->method, "given");
  EXPECT_LT((l->landmark.p - moved.p).norm(), test::kExactMm);
  const ArchLandmark* added = a.Find(36, LandmarkType::kCentralFossa);
  ASSERT_NE(added, nullptr);
  EXPECT_EQ(added->source, LandmarkSource::kGiven);
  for (const ArchLandmark& x : a.landmarks) EXPECT_EQ(x.landmark.jaw, Jaw::kLower);
}

TEST(ArchAnalysis, AMeshWithoutTeethIsAnErrorResult) {
  const ArchAnalysis empty = AnalyzeArch(io::TriangleMesh{}, Jaw::kLower);
  EXPECT_FALSE(empty.ok());
  const ArchAnalysis box = AnalyzeArch(
      test::MakeBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(40, 30, 10)), Jaw::kUpper);
  EXPECT_FALSE(box.ok());
  EXPECT_NE(box.error.find("no tooth"), std::string::npos) << box.error;
  const ArchAnalysis sphere = AnalyzeArch(test::MakeSphere({0, 0, 0}, 20, 24, 48), Jaw::kLower);
  EXPECT_FALSE(sphere.ok());
  EXPECT_TRUE(sphere.teeth.empty());
  // A single triangle and a jaw-sized box in metres (a few hundredths of a millimetre): too
  // few crown cells for any arch, an error result rather than an exception.
  io::TriangleMesh triangle;
  triangle.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  triangle.triangles = {{0, 1, 2}};
  EXPECT_FALSE(AnalyzeArch(triangle, Jaw::kLower).ok());
  const ArchAnalysis metres = AnalyzeArch(
      test::MakeBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.04, 0.03, 0.01)), Jaw::kLower);
  EXPECT_NE(metres.error.find("no tooth"), std::string::npos) << metres.error;
}

TEST(ArchAnalysis, OptionsOutOfRangeThrowNamingTheOption) {
  ArchAnalysisOptions o;
  o.grid_mm = 0.0;
  try {
    AnalyzeArch(Pair().lower_L, Jaw::kLower, o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("grid_mm"), std::string::npos) << e.what();
  }
}

// The c-cases (single-surface scans): 14 teeth numbered right to left, and the incisal edges
// near the hand-placed ones (issue target 0.5 mm median; measured in docs/results/analysis).
TEST(ArchAnalysis, CaseScansAreSegmentedAndNumbered) {
  for (const std::string name : {"c1-ios-decimated", "c4-ios-decimated"}) {
    OCCLUDE_REQUIRE_CASE(dir, name);
    const std::vector<io::Landmark> given = io::ReadLandmarkFile(dir / "landmarks.csv");
    for (const Jaw jaw : {Jaw::kLower, Jaw::kUpper}) {
      const ArchAnalysis a =
          AnalyzeArch(io::LoadMesh(dir / (std::string(io::ToString(jaw)) + ".stl")), jaw);
      ASSERT_TRUE(a.ok()) << name << ": " << a.error;
      EXPECT_EQ(Fdis(a), FullArch(jaw)) << name;
      for (const io::Landmark& g : given) {
        if (g.jaw != jaw || g.type != LandmarkType::kIncisalEdge) continue;
        const ArchLandmark* d = a.Find(g.tooth_fdi, g.type);
        ASSERT_NE(d, nullptr) << name << " " << g.tooth_fdi;
        EXPECT_LT((d->landmark.p - g.p).norm(), kCaseIncisalMm) << name << " " << g.tooth_fdi;
      }
    }
  }
}

}  // namespace
}  // namespace occlude::analysis
