// Saved oracles: the header and section framing, the checks done before any byte is trusted,
// the cache key, and the file side (atomic writes, one-pass reads).
#include "occlude/collision/oracle_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <system_error>
#include <utility>

#include "occlude/io/atomic_file.h"
#include "occlude/io/content_hash.h"
#include "oracle_codec.h"

namespace occlude::collision {
namespace {

constexpr char kMagic[8] = {'O', 'C', 'C', 'L', 'O', 'R', 'C', 'L'};
constexpr std::size_t kHeaderBytes = 48;
constexpr std::size_t kHeaderHashed = 40;  // the header bytes its own checksum covers
constexpr std::size_t kSectionHeaderBytes = 16;

struct Header {
  std::uint32_t version = kOracleFileVersion;
  std::uint32_t sections = 0;
  std::uint64_t key = 0;
  std::uint64_t payload_bytes = 0;
  std::uint64_t payload_checksum = 0;
};

template <typename T>
T ReadAt(std::string_view bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

template <typename T>
void Append(T value, std::string* out) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

[[noreturn]] void Fail(OracleFileProblem problem, const std::string& what) {
  throw OracleFileError(problem, what);
}

std::string EncodeHeader(const Header& h) {
  std::string out(kMagic, sizeof(kMagic));
  Append(h.version, &out);
  Append(h.sections, &out);
  Append(h.key, &out);
  Append(h.payload_bytes, &out);
  Append(h.payload_checksum, &out);
  Append(io::Hash64(out.data(), kHeaderHashed), &out);
  return out;
}

// The header of `bytes`, after the magic, version, header checksum and total size checks.
Header DecodeHeader(std::string_view bytes) {
  const std::size_t magic = std::min(bytes.size(), sizeof(kMagic));
  if (std::memcmp(bytes.data(), kMagic, magic) != 0)
    Fail(OracleFileProblem::kForeign, "not a saved oracle (no OCCLORCL magic)");
  if (bytes.size() < kHeaderBytes) {
    Fail(OracleFileProblem::kTruncated, "truncated: " + std::to_string(bytes.size()) +
                                            " bytes, less than the " +
                                            std::to_string(kHeaderBytes) + "-byte header");
  }
  Header h;
  h.version = ReadAt<std::uint32_t>(bytes, 8);
  if (h.version != kOracleFileVersion) {
    Fail(OracleFileProblem::kVersion, "format version " + std::to_string(h.version) +
                                          ", this build reads version " +
                                          std::to_string(kOracleFileVersion));
  }
  if (ReadAt<std::uint64_t>(bytes, kHeaderHashed) != io::Hash64(bytes.data(), kHeaderHashed))
    Fail(OracleFileProblem::kCorrupt, "corrupt: the header's checksum does not match");
  h.sections = ReadAt<std::uint32_t>(bytes, 12);
  h.key = ReadAt<std::uint64_t>(bytes, 16);
  h.payload_bytes = ReadAt<std::uint64_t>(bytes, 24);
  h.payload_checksum = ReadAt<std::uint64_t>(bytes, 32);
  const std::uint64_t have = bytes.size() - kHeaderBytes;
  if (have < h.payload_bytes) {
    Fail(OracleFileProblem::kTruncated, "truncated: " + std::to_string(have) + " of " +
                                            std::to_string(h.payload_bytes) + " payload bytes");
  }
  if (have > h.payload_bytes) {
    Fail(OracleFileProblem::kCorrupt,
         "corrupt: " + std::to_string(have - h.payload_bytes) + " bytes after the payload");
  }
  return h;
}

// The sections of the payload (tag, offset of the section header, size with it).
std::vector<OracleFileSection> SplitSections(std::string_view bytes, const Header& h) {
  std::vector<OracleFileSection> sections;
  std::size_t at = kHeaderBytes;
  for (std::uint32_t i = 0; i < h.sections; ++i) {
    if (bytes.size() - at < kSectionHeaderBytes)
      Fail(OracleFileProblem::kCorrupt, "corrupt: section " + std::to_string(i) + " ends early");
    const auto size = ReadAt<std::uint64_t>(bytes, at + 8);
    if (size > bytes.size() - at - kSectionHeaderBytes)
      Fail(OracleFileProblem::kCorrupt, "corrupt: section " + std::to_string(i) + " too long");
    sections.push_back({std::string(bytes.substr(at, 4)), at,
                        static_cast<std::size_t>(size) + kSectionHeaderBytes});
    at += sections.back().size;
  }
  if (at != bytes.size())
    Fail(OracleFileProblem::kCorrupt, "corrupt: bytes after the last section");
  return sections;
}

// The sections' payloads in the codec's tag order (each tag once, in that order).
std::vector<std::string_view> CheckedPayloads(std::string_view bytes, const Header& h) {
  const std::vector<OracleFileSection> sections = SplitSections(bytes, h);
  const std::vector<std::string>& tags = detail::OracleCodec::Tags();
  if (sections.size() != tags.size())
    Fail(OracleFileProblem::kCorrupt, "corrupt: " + std::to_string(sections.size()) + " sections");
  std::vector<std::string_view> payloads;
  for (std::size_t i = 0; i < tags.size(); ++i) {
    if (sections[i].tag != tags[i])
      Fail(OracleFileProblem::kCorrupt, "corrupt: section '" + sections[i].tag + "' unexpected");
    payloads.push_back(bytes.substr(sections[i].offset + kSectionHeaderBytes,
                                    sections[i].size - kSectionHeaderBytes));
  }
  return payloads;
}

void CheckMesh(const std::shared_ptr<const io::TriangleMesh>& mesh, const char* which) {
  if (mesh == nullptr)
    throw std::invalid_argument(std::string("LoadOracle: the ") + which + " mesh is null");
}

}  // namespace

const char* ToString(OracleFileProblem problem) {
  switch (problem) {
    case OracleFileProblem::kForeign:
      return "foreign";
    case OracleFileProblem::kVersion:
      return "version";
    case OracleFileProblem::kTruncated:
      return "truncated";
    case OracleFileProblem::kCorrupt:
      return "corrupt";
    case OracleFileProblem::kMismatch:
      return "mismatch";
    case OracleFileProblem::kUnreadable:
      return "unreadable";
  }
  return "?";
}

std::uint64_t OracleCacheKey(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U,
                             const OracleOptions& options) {
  return OracleCacheKey(io::MeshContentHash(lower_L), io::MeshContentHash(upper_U), options);
}

std::uint64_t OracleCacheKey(std::uint64_t lower_hash, std::uint64_t upper_hash,
                             const OracleOptions& options) {
  io::Hasher64 h;
  h.AddString("occlude saved oracle");
  h.AddValue(kOracleFileVersion);
  h.AddValue(lower_hash);
  h.AddValue(upper_hash);
  for (const double v : {options.voxel_size_mm, options.sample_spacing_mm, options.field_bound_mm,
                         options.field_bound_depth_mm}) {
    h.AddValue(v);
  }
  for (const int v : {options.sdf_dilation_voxels, options.cell_level, options.lower_level})
    h.AddValue(v);
  h.AddValue(static_cast<std::uint8_t>(options.distance_bound));
  h.AddValue(static_cast<std::uint8_t>(options.tree_queries));
  h.AddValue(static_cast<std::uint8_t>(options.arch.has_value()));
  if (options.arch) {
    const ArchFrame& a = *options.arch;
    for (const Eigen::Vector3d& v : {a.origin_L, a.occlusal_L, a.anterior_L, a.lateral_L})
      h.Add(v.data(), sizeof(double) * 3);
    h.AddValue(a.anterior_split_mm);
  }
  return h.Finish();
}

namespace {

// Writes the oracle's sections in order, each its tag, a reserved word, its size and its
// payload, handed to `put` in pieces (a section is measured first, then written: its size
// leads it); returns the header of the payload put (its size and checksum).
Header PutSections(const JawOracle& oracle, const detail::ByteSink& put) {
  const std::vector<std::string>& tags = detail::OracleCodec::Tags();
  io::Hasher64 checksum;
  std::uint64_t payload_bytes = 0;
  const detail::ByteSink hashed = [&](std::string_view piece) {
    checksum.Add(piece.data(), piece.size());
    payload_bytes += piece.size();
    put(piece);
  };
  for (std::size_t i = 0; i < tags.size(); ++i) {
    std::uint64_t size = 0;
    const detail::ByteSink count = [&size](std::string_view piece) { size += piece.size(); };
    detail::ByteWriter measure(&count);
    detail::OracleCodec::PutSection(oracle, i, &measure);
    measure.Flush();
    std::string head = tags[i];
    Append(std::uint32_t{0}, &head);
    Append(size, &head);
    hashed(head);
    detail::ByteWriter writer(&hashed);
    detail::OracleCodec::PutSection(oracle, i, &writer);
    writer.Flush();
  }
  Header h;
  h.sections = static_cast<std::uint32_t>(tags.size());
  h.key = OracleCacheKey(oracle.lower_tree().mesh(), oracle.upper_tree().mesh(),
                         detail::OracleCodec::Options(oracle));
  h.payload_bytes = payload_bytes;
  h.payload_checksum = checksum.Finish();
  return h;
}

}  // namespace

std::string SaveOracle(const JawOracle& oracle) {
  // One buffer, sized up front: the sections hold about what the oracle holds in memory.
  std::string out;
  out.reserve(kHeaderBytes + oracle.MemoryBytes() + (std::size_t{1} << 20));
  out.resize(kHeaderBytes);
  const Header h = PutSections(oracle, [&out](std::string_view section) { out += section; });
  const std::string header = EncodeHeader(h);
  std::memcpy(&out[0], header.data(), kHeaderBytes);
  return out;
}

namespace {

// LoadOracle of the meshes and options whose OracleCacheKey is `key`, telling `release`
// (optional) of the bytes it is done with: the payload in chunks as it is checksummed, then
// every array once copied out.
JawOracle LoadReleasing(std::string_view bytes, std::shared_ptr<const io::TriangleMesh> lower_L,
                        std::shared_ptr<const io::TriangleMesh> upper_U,
                        const OracleOptions& options, std::uint64_t key,
                        const detail::ReleaseBytes* release) {
  const Header h = DecodeHeader(bytes);
  if (h.key != key) {
    Fail(OracleFileProblem::kMismatch,
         "saved for other meshes or options (key " + io::HashHex(h.key) + ")");
  }
  constexpr std::size_t kChunk = std::size_t{16} << 20;
  io::Hasher64 payload;
  for (std::size_t at = kHeaderBytes; at < bytes.size(); at += kChunk) {
    const std::size_t n = std::min(kChunk, bytes.size() - at);
    payload.Add(bytes.data() + at, n);
    if (release != nullptr) (*release)(bytes.data() + at, n);
  }
  if (payload.Finish() != h.payload_checksum)
    Fail(OracleFileProblem::kCorrupt, "corrupt: the payload's checksum does not match");
  return detail::OracleCodec::Assemble(CheckedPayloads(bytes, h), std::move(lower_L),
                                       std::move(upper_U), options, release);
}

}  // namespace

JawOracle LoadOracle(std::string_view bytes, std::shared_ptr<const io::TriangleMesh> lower_L,
                     std::shared_ptr<const io::TriangleMesh> upper_U,
                     const OracleOptions& options) {
  CheckMesh(lower_L, "lower");
  CheckMesh(upper_U, "upper");
  const std::uint64_t key = OracleCacheKey(*lower_L, *upper_U, options);
  return LoadReleasing(bytes, std::move(lower_L), std::move(upper_U), options, key, nullptr);
}

std::vector<OracleFileSection> DescribeOracleBytes(std::string_view bytes) {
  const Header h = DecodeHeader(bytes);
  std::vector<OracleFileSection> sections = {{"head", 0, kHeaderBytes}};
  for (OracleFileSection& s : SplitSections(bytes, h)) sections.push_back(std::move(s));
  return sections;
}

void SaveOracleFile(const JawOracle& oracle, const std::filesystem::path& file,
                    io::Durability durability) {
  // In pieces, so that little besides the oracle is held; the header, known at the end, goes in
  // front.
  io::AtomicFileWriter out(file, durability);
  out.Append(std::string(kHeaderBytes, '\0'));
  const Header h = PutSections(oracle, [&out](std::string_view section) { out.Append(section); });
  out.Overwrite(0, EncodeHeader(h));
  out.Commit();
}

namespace {

// A read-only private mapping of a whole file, read in order (MADV_SEQUENTIAL: read ahead);
// Release drops the whole pages of a range already read (they stay in the page cache, so a
// second read is a minor fault), so that a loaded oracle and its file are not resident at once;
// unmapped when the object dies.
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) Fail(file, "cannot open", errno);
    struct stat status {};
    if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
      const int error = errno;
      ::close(fd);
      Fail(file, "not a regular file", error);
    }
    size_ = static_cast<std::size_t>(status.st_size);
    if (size_ > 0) {
      data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (data_ != MAP_FAILED) ::madvise(data_, size_, MADV_SEQUENTIAL);
    }
    const int error = errno;
    ::close(fd);
    if (data_ == MAP_FAILED) Fail(file, "cannot map", error);
  }
  ~MappedFile() {
    if (data_ != MAP_FAILED && data_ != nullptr) ::munmap(data_, size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::string_view bytes() const {
    return size_ == 0 ? std::string_view()
                      : std::string_view(static_cast<const char*>(data_), size_);
  }
  /// Drops the resident pages that lie wholly inside [data, data + size) (a range of bytes()).
  void Release(const char* data, std::size_t size) const {
    static const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    // Offsets from the mapping's start (page aligned), so the pointer stays one of the mapping's.
    char* const base = static_cast<char*>(data_);
    const auto begin = static_cast<std::uintptr_t>(data - base);
    const std::uintptr_t first = (begin + page - 1) / page * page;
    const std::uintptr_t last = (begin + size) / page * page;
    if (last > first) ::madvise(base + first, last - first, MADV_DONTNEED);
  }

 private:
  [[noreturn]] static void Fail(const std::filesystem::path& file, const char* what, int error) {
    throw OracleFileError(OracleFileProblem::kUnreadable,
                          file.string() + ": " + what + ": " +
                              std::error_code(error, std::generic_category()).message());
  }
  void* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace

JawOracle LoadOracleFile(const std::filesystem::path& file,
                         std::shared_ptr<const io::TriangleMesh> lower_L,
                         std::shared_ptr<const io::TriangleMesh> upper_U,
                         const OracleOptions& options) {
  CheckMesh(lower_L, "lower");
  CheckMesh(upper_U, "upper");
  const std::uint64_t key = OracleCacheKey(*lower_L, *upper_U, options);
  return LoadOracleFile(file, std::move(lower_L), std::move(upper_U), options, key);
}

JawOracle LoadOracleFile(const std::filesystem::path& file,
                         std::shared_ptr<const io::TriangleMesh> lower_L,
                         std::shared_ptr<const io::TriangleMesh> upper_U,
                         const OracleOptions& options, std::uint64_t key) {
  CheckMesh(lower_L, "lower");
  CheckMesh(upper_U, "upper");
  const MappedFile mapped(file);
  const detail::ReleaseBytes release = [&mapped](const char* data, std::size_t size) {
    mapped.Release(data, size);
  };
  try {
    return LoadReleasing(mapped.bytes(), std::move(lower_L), std::move(upper_U), options, key,
                         &release);
  } catch (const OracleFileError& e) {
    Fail(e.problem(), file.string() + ": " + e.what());
  }
}

}  // namespace occlude::collision
