// A region-of-interest selection as a cache entry (session/region_entry.h): it decodes to the
// selection (the same kept triangles and sub-meshes, vertex for vertex, whole meshes shared) on
// the synthetic pair, cut and whole; any malformed entry throws; the key changes with a mesh
// byte and every request field; and a session reads its selections from a warm cache, after a
// bad entry too, with the models and answers of the cold session.
#include "session/region_entry.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "config/case_config.h"
#include "occlude/io/content_hash.h"
#include "session/case_session.h"
#include "session/jaw_pair.h"
#include "test_common.h"

namespace occlude::app {
namespace {

namespace fs = std::filesystem;
using collision::RegionOfInterest;
using collision::RegionOfInterestRequest;

// The app's synthetic pair (session/jaw_pair.h), 5,000 triangles a jaw, seed 2.
const JawPair& RegionTestJaws() {
  static const JawPair pair = SyntheticJawPair(5000, 2);
  return pair;
}

RegionOfInterestRequest RegionTestRequest(double band_mm) {
  RegionOfInterestRequest r;
  r.X_LU_start = RegionTestJaws().X_LU_ref;
  r.pivot_L = RegionTestJaws().X_LU_ref.translation();
  for (std::size_t d = 0; d < 6; ++d) {
    r.bound_min[d] = d < 3 ? -1.0 : -2.0;
    r.bound_max[d] = d < 3 ? 1.0 : 2.0;
  }
  r.band_mm = band_mm;
  return r;
}

void ExpectSameRegion(const RegionOfInterest& a, const RegionOfInterest& b) {
  for (const auto& [x, y] : {std::pair{&a.lower, &b.lower}, {&a.upper, &b.upper}}) {
    EXPECT_EQ(y->original_triangle, x->original_triangle);
    EXPECT_EQ(io::MeshContentHash(*y->mesh), io::MeshContentHash(*x->mesh));
  }
  EXPECT_EQ(a.lower.mesh == RegionTestJaws().lower_L, b.lower.mesh == RegionTestJaws().lower_L);
  EXPECT_EQ(a.upper.mesh == RegionTestJaws().upper_U, b.upper.mesh == RegionTestJaws().upper_U);
  EXPECT_EQ(a.stats.band_mm, b.stats.band_mm);
  EXPECT_EQ(a.stats.displacement_mm, b.stats.displacement_mm);
  EXPECT_EQ(a.stats.reach_mm, b.stats.reach_mm);
  EXPECT_EQ(a.stats.lower_kept, b.stats.lower_kept);
  EXPECT_EQ(a.stats.upper_kept, b.stats.upper_kept);
  EXPECT_EQ(a.stats.lower_total, b.stats.lower_total);
}

TEST(RegionEntryTest, DecodesToTheSelectionCutAndWhole) {
  const JawPair& p = RegionTestJaws();
  std::size_t cut = 0;
  for (const double band : {0.3, 1.0, 1000.0}) {
    const RegionOfInterest made =
        collision::ComputeRegionOfInterest(p.lower_L, p.upper_U, RegionTestRequest(band));
    cut += made.stats.lower_total - made.stats.lower_kept + made.stats.upper_total -
           made.stats.upper_kept;
    const RegionOfInterest read = DecodeRegion(EncodeRegion(made), p.lower_L, p.upper_U);
    ExpectSameRegion(made, read);
    EXPECT_GE(read.stats.seconds, 0.0);
  }
  EXPECT_GT(cut, 0u);  // some band cut a jaw: not only whole meshes compared
}

TEST(RegionEntryTest, MalformedEntriesThrow) {
  const JawPair& p = RegionTestJaws();
  const std::string good = EncodeRegion(
      collision::ComputeRegionOfInterest(p.lower_L, p.upper_U, RegionTestRequest(0.3)));
  ASSERT_GT(good.size(), 40u);
  auto throws = [&](const std::string& bytes) {
    EXPECT_THROW(DecodeRegion(bytes, p.lower_L, p.upper_U), std::runtime_error);
  };
  throws("");
  throws(good.substr(0, good.size() - 1));  // truncated
  throws(good + "x");                       // trailing bytes
  std::string other = good;
  other[0] = 9;  // another encoding version
  throws(other);
  // The closed lower is kept whole (a 4-byte mark), the upper cut: its list follows its count.
  const std::size_t upper_first = 4 + 3 * 8 + 4 + 4;
  ASSERT_GT(good.size(), upper_first + 8);
  std::string unordered = good;  // the upper's first kept index raised beyond its triangles
  unordered[upper_first + 3] = static_cast<char>(0x7f);
  throws(unordered);
  // The list does not fit an upper with fewer triangles.
  auto small = std::make_shared<io::TriangleMesh>(*p.upper_U);
  small->triangles.resize(10);
  small->triangle_part.resize(std::min<std::size_t>(small->triangle_part.size(), 10));
  small->face_normals.resize(std::min<std::size_t>(small->face_normals.size(), 10));
  EXPECT_THROW(DecodeRegion(good, p.lower_L, small), std::runtime_error);
}

TEST(RegionEntryTest, KeyChangesWithAMeshByteAndEveryRequestField) {
  const JawPair& p = RegionTestJaws();
  const RegionOfInterestRequest base = RegionTestRequest(1.0);
  const std::uint64_t key = RegionEntryKey(*p.lower_L, *p.upper_U, base);
  EXPECT_EQ(RegionEntryKey(*p.lower_L, *p.upper_U, base), key);
  EXPECT_EQ(RegionEntryKey(io::MeshContentHash(*p.lower_L), io::MeshContentHash(*p.upper_U), base),
            key);  // from the meshes' hashes
  io::TriangleMesh moved = *p.upper_U;
  moved.vertices[7].x() = std::nextafter(moved.vertices[7].x(), 1e9);
  EXPECT_NE(RegionEntryKey(*p.lower_L, moved, base), key);
  std::vector<RegionOfInterestRequest> changed(7, base);
  changed[0].band_mm = 1.5;
  changed[1].voxel_size_mm = 0.25;
  changed[2].bound_min[4] = -3.0;
  changed[3].bound_max[0] = 2.0;
  changed[4].locked[5] = true;
  changed[5].pivot_L.z() += 0.1;
  changed[6].X_LU_start.translation().y() += 0.1;
  for (std::size_t i = 0; i < changed.size(); ++i)
    EXPECT_NE(RegionEntryKey(*p.lower_L, *p.upper_U, changed[i]), key) << i;
}

// The models a session lists and the answers of its finest oracle, for comparing sessions.
struct RegionTestSession {
  std::vector<collision::RegionOfInterestStats> regions;
  std::uint64_t answers = 0;
};

RegionTestSession ViewOfSession(const CaseConfig& config) {
  CaseSession session(config);
  RegionTestSession v;
  const planner::OracleSchedule& schedule = session.Schedule();
  for (const OracleModel& m : session.Models()) {
    EXPECT_TRUE(m.region.has_value());
    if (m.region) v.regions.push_back(*m.region);
  }
  io::Hasher64 hash;
  collision::OracleResult result;
  schedule.back().oracle->Query(Eigen::Isometry3d::Identity(), collision::OracleRequest{}, &result);
  collision::HashOracleResult(result, &hash);
  v.answers = hash.Finish();
  return v;
}

std::vector<fs::path> RegionEntries(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.path().filename().string().rfind("region-", 0) == 0) out.push_back(e.path());
  }
  return out;
}

TEST(RegionEntryTest, SessionReadsItsSelectionsFromAWarmCache) {
  const test::TempDir dir;
  CaseConfig config = ParseCaseConfig(
      "[synthetic]\ntriangles = 5000\nseed = 1\n[bounds]\ntx_mm = [-1, 1]\nty_mm = [-1, 1]\n"
      "tz_mm = [-1, 1]\nrx_deg = [-2, 2]\nry_deg = [-2, 2]\nrz_deg = [-2, 2]\n",
      "synthetic.toml");
  config.cache_folder = dir.path();
  const RegionTestSession cold = ViewOfSession(config);
  ASSERT_EQ(cold.regions.size(), 3u);
  EXPECT_EQ(RegionEntries(dir.path()).size(), 3u);  // one selection per stage's band
  for (const bool garbled : {false, true}) {
    const auto old = fs::file_time_type::clock::now() - std::chrono::hours(24);
    for (const fs::path& entry : RegionEntries(dir.path())) fs::last_write_time(entry, old);
    if (garbled) {  // a bad entry is made again, not trusted
      const fs::path entry = RegionEntries(dir.path()).front();
      std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(-1, std::ios::end);
      f.put('\x5a');
    }
    const RegionTestSession warm = ViewOfSession(config);
    ASSERT_EQ(warm.regions.size(), cold.regions.size());
    for (std::size_t i = 0; i < warm.regions.size(); ++i) {
      EXPECT_EQ(warm.regions[i].reach_mm, cold.regions[i].reach_mm) << i;
      EXPECT_EQ(warm.regions[i].lower_kept, cold.regions[i].lower_kept) << i;
      EXPECT_EQ(warm.regions[i].upper_kept, cold.regions[i].upper_kept) << i;
    }
    EXPECT_EQ(warm.answers, cold.answers) << garbled;
    for (const fs::path& entry : RegionEntries(dir.path()))  // read (touched) or made again
      EXPECT_GT(fs::last_write_time(entry), old + std::chrono::hours(1)) << entry;
  }
}

}  // namespace
}  // namespace occlude::app
