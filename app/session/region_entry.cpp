// The region selection cache entry (region_entry.h): little-endian fixed-size fields, then per
// jaw a count and the kept triangle indices (the count UINT32_MAX for a jaw kept whole).
#include "session/region_entry.h"

#include <chrono>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "occlude/io/content_hash.h"
#include "session/byte_fields.h"

namespace occlude::app {
namespace {

constexpr std::uint32_t kEncodingVersion = 1;
constexpr std::uint32_t kWhole = std::numeric_limits<std::uint32_t>::max();

void PutKept(const collision::RegionMesh& jaw, std::size_t total, std::string* out) {
  const std::vector<std::uint32_t>& kept = jaw.original_triangle;
  if (kept.size() == total && total > 0) {  // the whole mesh (shared, not copied)
    PutValue(out, kWhole);
    return;
  }
  PutValue(out, static_cast<std::uint32_t>(kept.size()));
  out->append(reinterpret_cast<const char*>(kept.data()), kept.size() * sizeof(std::uint32_t));
}

// Reads the bytes in order; every read checks that the bytes hold it.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    Need(sizeof(T));
    const T value = ValueAt<T>(bytes_, at_);
    at_ += sizeof(T);
    return value;
  }
  std::vector<std::uint32_t> Kept(std::size_t total) {
    const auto count = Get<std::uint32_t>();
    if (count == kWhole) {
      std::vector<std::uint32_t> all(total);
      std::iota(all.begin(), all.end(), 0u);
      return all;
    }
    if (count > total) throw std::runtime_error("more kept triangles than the mesh has");
    std::vector<std::uint32_t> kept(count);
    Need(kept.size() * sizeof(std::uint32_t));
    std::memcpy(kept.data(), bytes_.data() + at_, kept.size() * sizeof(std::uint32_t));
    at_ += kept.size() * sizeof(std::uint32_t);
    return kept;
  }
  void ExpectEnd() const {
    if (at_ != bytes_.size()) throw std::runtime_error("bytes after the selection");
  }

 private:
  void Need(std::size_t size) const {
    if (bytes_.size() - at_ < size) throw std::runtime_error("truncated selection");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::uint64_t RegionEntryKey(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U,
                             const collision::RegionOfInterestRequest& request) {
  return RegionEntryKey(io::MeshContentHash(lower_L), io::MeshContentHash(upper_U), request);
}

std::uint64_t RegionEntryKey(std::uint64_t lower_hash, std::uint64_t upper_hash,
                             const collision::RegionOfInterestRequest& request) {
  io::Hasher64 h;
  h.AddString("occlude region of interest");
  h.AddValue(kEncodingVersion);
  h.AddString(collision::RegionSelectionCodeVersion());
  h.AddValue(lower_hash);
  h.AddValue(upper_hash);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) h.AddValue(request.X_LU_start.matrix()(r, c));
  }
  for (int a = 0; a < 3; ++a) h.AddValue(request.pivot_L[a]);
  for (std::size_t d = 0; d < 6; ++d) {
    h.AddValue(request.bound_min[d]);
    h.AddValue(request.bound_max[d]);
    h.AddValue(static_cast<std::uint8_t>(request.locked[d] ? 1 : 0));
  }
  h.AddValue(request.band_mm);
  h.AddValue(request.voxel_size_mm);
  return h.Finish();
}

std::string EncodeRegion(const collision::RegionOfInterest& roi) {
  std::string out;
  PutValue(&out, kEncodingVersion);
  for (const double v : {roi.stats.band_mm, roi.stats.displacement_mm, roi.stats.reach_mm})
    PutValue(&out, v);
  PutKept(roi.lower, roi.stats.lower_total, &out);
  PutKept(roi.upper, roi.stats.upper_total, &out);
  return out;
}

collision::RegionOfInterest DecodeRegion(std::string_view bytes,
                                         const std::shared_ptr<const io::TriangleMesh>& lower_L,
                                         const std::shared_ptr<const io::TriangleMesh>& upper_U) {
  const auto start = std::chrono::steady_clock::now();
  Reader in(bytes);
  if (in.Get<std::uint32_t>() != kEncodingVersion)
    throw std::runtime_error("a selection of another encoding");
  collision::RegionOfInterestStats stats;
  stats.band_mm = in.Get<double>();
  stats.displacement_mm = in.Get<double>();
  stats.reach_mm = in.Get<double>();
  std::vector<std::uint32_t> lower_kept = in.Kept(lower_L->num_triangles());
  std::vector<std::uint32_t> upper_kept = in.Kept(upper_U->num_triangles());
  in.ExpectEnd();
  collision::RegionOfInterest roi;
  try {
    roi = collision::RegionOfKept(lower_L, upper_U, std::move(lower_kept), std::move(upper_kept),
                                  stats);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  roi.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return roi;
}

}  // namespace occlude::app
