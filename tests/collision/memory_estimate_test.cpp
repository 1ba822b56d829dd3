// The memory estimates against real builds: the synthetic jaw pair at several
// triangle budgets and voxel sizes, each estimate within kFactor of what the
// built structure reports; and the fitting-voxel search on an analytic model.
#include "occlude/collision/memory_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

// The estimates come from the surface area and counts alone; on the synthetic
// pair and the real jaws (0.1-0.8 mm) they were within 0.9-1.25 of the built
// sizes. 1.5 leaves room for storage changes, not for a wrong model.
constexpr double kFactor = 1.5;

struct Pair {
  std::shared_ptr<const io::TriangleMesh> lower_L, upper_U;
};

Pair MakePair(std::size_t triangles) {
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = triangles;
  const io::SyntheticJawPair pair = io::MakeSyntheticJawPair(options);
  return {std::make_shared<io::TriangleMesh>(pair.lower_L),
          std::make_shared<io::TriangleMesh>(pair.upper_U)};
}

// Checks and prints (for the README's figures) estimate / built.
void ExpectWithinFactor(std::size_t estimate, std::size_t measured, const std::string& what) {
  const double ratio = static_cast<double>(estimate) / static_cast<double>(measured);
  std::printf("memory estimate: %-48s estimate %8.1f MB, built %8.1f MB, ratio %.2f\n",
              what.c_str(), static_cast<double>(estimate) / 1e6,
              static_cast<double>(measured) / 1e6, ratio);
  EXPECT_LT(ratio, kFactor) << what << ": estimate " << estimate << ", built " << measured;
  EXPECT_GT(ratio, 1.0 / kFactor) << what << ": estimate " << estimate << ", built " << measured;
}

struct Size {
  std::size_t triangles;
  double voxel_mm;
  bool oracle;  ///< also build the oracle (slow at fine voxels, above all in the sanitizer lane)
};

class MemoryEstimateTest : public ::testing::TestWithParam<Size> {};

TEST_P(MemoryEstimateTest, TreesOracleAndFieldWithinFactorOfTheBuilt) {
  const auto [triangles, voxel_mm, oracle_wanted] = GetParam();
#ifdef OCCLUDE_SANITIZED
  // One oracle is enough there: the Debug sanitizer build takes minutes for the others.
  const bool with_oracle = oracle_wanted && triangles == 5000 && voxel_mm >= 0.8;
#else
  const bool with_oracle = oracle_wanted;
#endif
  const Pair pair = MakePair(triangles);
  SphereTreeOptions tree_options;
  tree_options.voxelize.voxel_size_mm = voxel_mm;
  const SphereTree tree = SphereTree::Build(pair.lower_L, tree_options);
  const MemoryEstimate tree_estimate = EstimateSphereTreeMemory(*pair.lower_L, tree_options);
  const std::string where = " (" + std::to_string(triangles) + " triangles, " +
                            std::to_string(voxel_mm).substr(0, 4) + " mm)";
  ExpectWithinFactor(tree_estimate.resident_bytes, tree.stats().total_bytes(),
                     "sphere tree" + where);
  EXPECT_GE(tree_estimate.peak_bytes, tree_estimate.resident_bytes);

  if (with_oracle) {
    OracleOptions oracle_options;
    oracle_options.voxel_size_mm = voxel_mm;
    const JawOracle oracle(pair.lower_L, pair.upper_U, oracle_options);
    const MemoryEstimate oracle_estimate =
        EstimateOracleMemory(*pair.lower_L, *pair.upper_U, oracle_options);
    ExpectWithinFactor(oracle_estimate.resident_bytes, oracle.MemoryBytes(), "oracle" + where);
    EXPECT_GE(oracle_estimate.peak_bytes, oracle_estimate.resident_bytes);
  }

  // A surface-only field without dilation, as the report's contact maps build it.
  VoxelizeOptions surface_only;
  surface_only.voxel_size_mm = voxel_mm;
  surface_only.classify_proximity = false;
  surface_only.classify_interior = false;
  NarrowBandOptions band;
  band.dilation_voxels = 0;
  const NarrowBandSdf field =
      NarrowBandSdf::Build(pair.upper_U, Voxelize(*pair.upper_U, surface_only), band);
  ExpectWithinFactor(EstimateNarrowBandSdfMemory(*pair.upper_U, voxel_mm, 0).resident_bytes,
                     field.MemoryBytes(), "narrow band field" + where);
}

INSTANTIATE_TEST_SUITE_P(SyntheticPair, MemoryEstimateTest,
                         ::testing::Values(Size{5000, 0.8, true}, Size{5000, 0.4, true},
                                           Size{20000, 0.8, true}, Size{5000, 0.2, false},
                                           Size{20000, 0.2, false}),
                         [](const ::testing::TestParamInfo<Size>& param_info) {
                           return "triangles" + std::to_string(param_info.param.triangles) +
                                  "_voxel" +
                                  std::to_string(std::lround(param_info.param.voxel_mm * 1000)) +
                                  "um";
                         });

// The real registered bite (137k / 148k triangles), when the shared data is there.
TEST(MemoryEstimate, RealJawsWithinFactorOfTheBuilt) {
  OCCLUDE_REQUIRE_CASE(dir, "a-bite-3shape");
  const auto lower = std::make_shared<io::TriangleMesh>(io::LoadMesh(dir / "lower.stl"));
  const auto upper = std::make_shared<io::TriangleMesh>(io::LoadMesh(dir / "upper.stl"));
#ifdef OCCLUDE_SANITIZED
  const double voxels_mm[] = {0.8};  // the Debug sanitizer build takes minutes per oracle here
#else
  const double voxels_mm[] = {0.8, 0.4};
#endif
  for (const double voxel_mm : voxels_mm) {
    OracleOptions options;
    options.voxel_size_mm = voxel_mm;
    const JawOracle oracle(lower, upper, options);
    ExpectWithinFactor(EstimateOracleMemory(*lower, *upper, options).resident_bytes,
                       oracle.MemoryBytes(),
                       "oracle (a-bite-3shape, " + std::to_string(voxel_mm).substr(0, 4) + " mm)");
  }
  SphereTreeOptions tree_options;
  tree_options.voxelize.voxel_size_mm = 0.4;
  const SphereTree tree = SphereTree::Build(upper, tree_options);
  ExpectWithinFactor(EstimateSphereTreeMemory(*upper, tree_options).resident_bytes,
                     tree.stats().total_bytes(), "sphere tree (a-bite-3shape upper, 0.40 mm)");
}

TEST(MemoryEstimate, FinerVoxelsNeedMore) {
  const Pair pair = MakePair(5000);
  OracleOptions coarse, fine;
  coarse.voxel_size_mm = 0.4;
  fine.voxel_size_mm = 0.2;
  const auto a = EstimateOracleMemory(*pair.lower_L, *pair.upper_U, coarse);
  const auto b = EstimateOracleMemory(*pair.lower_L, *pair.upper_U, fine);
  EXPECT_GT(b.resident_bytes, a.resident_bytes);
  EXPECT_GT(b.peak_bytes, a.peak_bytes);
}

TEST(MemoryEstimate, SumKeepsOnePeakOnTopOfTheOthersResidents) {
  MemoryEstimate a{100, 300};
  a += MemoryEstimate{50, 80};
  EXPECT_EQ(a.resident_bytes, 150u);
  EXPECT_EQ(a.peak_bytes, 350u);  // max(300 + 50, 100 + 80)
}

TEST(MemoryEstimate, SmallestFittingVoxelOnAnAnalyticModel) {
  // bytes = C / s^2: fits the budget B from s* = sqrt(C / B).
  const double c = 4e8;
  const auto model = [c](double s) { return static_cast<std::size_t>(c / (s * s)); };
  const std::size_t budget = 1'000'000'000;  // s* = sqrt(0.4) = 0.632 mm
  const double s = SmallestFittingVoxelMm(model, 0.05, 5.0, budget);
  EXPECT_LE(model(s), budget);
  EXPECT_GT(s, std::sqrt(c / 1e9));
  EXPECT_LT(s, 1.005 * std::sqrt(c / 1e9));
  EXPECT_DOUBLE_EQ(SmallestFittingVoxelMm(model, 0.7, 5.0, budget), 0.7);  // already fits
  EXPECT_TRUE(std::isinf(SmallestFittingVoxelMm(model, 0.05, 5.0, 1000)));
}

TEST(MemoryEstimate, DefaultBudgetIsAQuarterOfTheMachine) {
  const std::size_t physical = PhysicalMemoryBytes();
  if (physical == 0) {
    EXPECT_EQ(DefaultMemoryBudgetBytes(), std::size_t{1} << 30);
  } else {
    EXPECT_EQ(DefaultMemoryBudgetBytes(), physical / 4);
  }
}

}  // namespace
}  // namespace occlude::collision
