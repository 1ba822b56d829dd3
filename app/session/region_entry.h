// A region-of-interest selection as a cache entry (session/oracle_cache.h, kind "region"): its
// key, and its bytes both ways. A selection depends on the two meshes and the request alone
// (collision/region_of_interest.h), so the key is both meshes' content hashes, every request
// field and a hash of the selection's code (collision::RegionSelectionCodeVersion()); decoding
// gives back the selection's sub-meshes vertex for vertex (collision::RegionOfKept), so an
// oracle on them has the key of the one built on the selection itself.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "occlude/collision/region_of_interest.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// The cache entry kind of region selections.
inline constexpr char kRegionEntryKind[] = "region";

/// The key of ComputeRegionOfInterest(lower_L, upper_U, request).
std::uint64_t RegionEntryKey(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U,
                             const collision::RegionOfInterestRequest& request);
/// The same from the meshes' io::MeshContentHash values (OracleCache::MeshHash).
std::uint64_t RegionEntryKey(std::uint64_t lower_hash, std::uint64_t upper_hash,
                             const collision::RegionOfInterestRequest& request);

/// The selection as bytes: its stats (but the seconds) and each jaw's kept triangles ("all" for
/// a jaw kept whole).
std::string EncodeRegion(const collision::RegionOfInterest& roi);
/// The selection EncodeRegion wrote, made again on these meshes (stats.seconds: the decoding's
/// wall time); throws std::runtime_error saying what is malformed or does not fit the meshes.
collision::RegionOfInterest DecodeRegion(std::string_view bytes,
                                         const std::shared_ptr<const io::TriangleMesh>& lower_L,
                                         const std::shared_ptr<const io::TriangleMesh>& upper_U);

}  // namespace occlude::app
