// Saved oracles (the paper's saved IST, for every structure a JawOracle builds): a built oracle
// as bytes and back, and the key a cache files them under.
//
// Format (little-endian, version kOracleFileVersion): a 48-byte header (magic "OCCLORCL",
// u32 version, u32 section count, u64 key, u64 payload bytes, u64 payload checksum, u64
// checksum of the header's first 40 bytes), then the payload: sections, each a u32 tag, u32
// zero, u64 size and that many bytes. Sections in order: the lower tree, the upper tree, the
// lower distance field, the field bound and the oracle's own arrays (samples, culling spheres,
// arch frame). Inside a section every array is its u64 element count and its elements' bytes.
// Checksums are io::Hash64. The meshes are not stored: the loader is given them, and their
// content hashes are part of the key.
//
// Trust: nothing in a file is used before the magic, the version, the header checksum, the
// total size, the key and the payload checksum have been checked; then every read is bounds
// checked and every array size checked against what the structure needs, so a file that
// passes the checksum by accident still cannot make the loader read out of bounds. A loaded
// oracle answers bit-identically to the one that was saved.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/collision/oracle.h"
#include "occlude/io/atomic_file.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

/// Bumped whenever the layout or what a build makes changes (older files are then rejected).
inline constexpr std::uint32_t kOracleFileVersion = 1;

/// Why saved bytes were not loaded.
enum class OracleFileProblem {
  kForeign,     ///< not a saved oracle (wrong magic)
  kVersion,     ///< another format version
  kTruncated,   ///< fewer bytes than the header says
  kCorrupt,     ///< checksum, size or structure wrong
  kMismatch,    ///< a saved oracle of other meshes or options (key differs)
  kUnreadable,  ///< the file cannot be read (missing, no permission)
};
const char* ToString(OracleFileProblem problem);

/// Thrown by LoadOracle*: what() says what is wrong ("<file>: ..." for files); the caller
/// rebuilds. Never thrown for a file that SaveOracle* wrote for the same key.
class OracleFileError : public std::runtime_error {
 public:
  OracleFileError(OracleFileProblem problem, const std::string& what)
      : std::runtime_error(what), problem_(problem) {}
  OracleFileProblem problem() const { return problem_; }

 private:
  OracleFileProblem problem_;
};

/// The cache key of the oracle of these meshes and options: the format version, both meshes'
/// io::MeshContentHash and every OracleOptions field except `threads` (which never changes
/// what is built): voxel_size_mm, sample_spacing_mm, sdf_dilation_voxels, cell_level,
/// lower_level, distance_bound, field_bound_mm, field_bound_depth_mm and arch (whether set,
/// and each of its fields). Bit-exact: any changed bit of any of them changes the key.
std::uint64_t OracleCacheKey(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U,
                             const OracleOptions& options);
/// The same from the meshes' io::MeshContentHash values, for a caller that hashed each mesh
/// once for all its keys.
std::uint64_t OracleCacheKey(std::uint64_t lower_hash, std::uint64_t upper_hash,
                             const OracleOptions& options);

/// The oracle as bytes (the format above), keyed by OracleCacheKey of its meshes and options.
std::string SaveOracle(const JawOracle& oracle);

/// The oracle saved in `bytes`, for these meshes and options (their key must be the saved
/// one). Throws OracleFileError (any problem of the bytes) or std::invalid_argument (null
/// mesh).
JawOracle LoadOracle(std::string_view bytes, std::shared_ptr<const io::TriangleMesh> lower_L,
                     std::shared_ptr<const io::TriangleMesh> upper_U, const OracleOptions& options);

/// SaveOracle's bytes into `file`, atomically (a temporary file in the same folder, then renamed
/// over it: a reader never sees a half-written file; flushed to disk first as `durability`
/// says), written in pieces of about a megabyte (an array is written from its own memory):
/// besides the oracle, next to nothing is held. Throws io::MeshError naming the file (folder
/// missing or not writable, disk full).
void SaveOracleFile(const JawOracle& oracle, const std::filesystem::path& file,
                    io::Durability durability = io::Durability::kDurable);

/// LoadOracle of the file's bytes, read in one pass. Throws OracleFileError naming the file
/// (also when it cannot be read).
JawOracle LoadOracleFile(const std::filesystem::path& file,
                         std::shared_ptr<const io::TriangleMesh> lower_L,
                         std::shared_ptr<const io::TriangleMesh> upper_U,
                         const OracleOptions& options);
/// The same with the meshes' and options' key given (OracleCacheKey of exactly these, from the
/// hashes the caller keeps): the saved key must be `key` (else kMismatch).
JawOracle LoadOracleFile(const std::filesystem::path& file,
                         std::shared_ptr<const io::TriangleMesh> lower_L,
                         std::shared_ptr<const io::TriangleMesh> upper_U,
                         const OracleOptions& options, std::uint64_t key);

/// One section of saved bytes (for tests and diagnostics): its tag, and where its bytes are.
struct OracleFileSection {
  std::string tag;
  std::size_t offset = 0;  ///< of the section's own header, from the start of the bytes
  std::size_t size = 0;    ///< section header included
};
/// The header (tag "head") and the sections of bytes that SaveOracle wrote. Throws
/// OracleFileError when the framing is broken.
std::vector<OracleFileSection> DescribeOracleBytes(std::string_view bytes);

}  // namespace occlude::collision
