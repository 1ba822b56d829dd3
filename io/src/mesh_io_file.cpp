// File-system side of mesh I/O: validated whole-file reads, atomic writes, and
// the one-line error/warning format "<path>: <what>".
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <system_error>

#include "mesh_io_internal.h"

namespace occlude::io::detail {
namespace {

namespace fs = std::filesystem;

// Larger files are refused before reading: jaw scans are a few tens of MB, and
// vertex indices are 32-bit.
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{2} << 30;

std::string ErrnoText(int error) {
  return std::error_code(error, std::generic_category()).message();
}

fs::path FolderOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

}  // namespace

// A temporary file beside the target that is removed unless Commit() succeeds.
class TempFile {
 public:
  explicit TempFile(const fs::path& target) : target_(target) { Create(); }
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) ::unlink(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  // Writes `bytes` at `offset`: past the end (appending) or over what was written; at most
  // kMaxWriteBytes a call (on the ext4 of the 2-core hosts, single writes of a few MB into the
  // page cache now and then took 10x as long: 132 MB in 15 MB writes 29-334 ms over eight runs,
  // in 1 MiB writes 24-30 ms).
  void WriteAt(std::size_t offset, std::string_view bytes) {
    constexpr std::size_t kMaxWriteBytes = std::size_t{1} << 20;
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n =
          ::pwrite(fd_, bytes.data() + done, std::min(bytes.size() - done, kMaxWriteBytes),
                   static_cast<off_t>(offset + done));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) FailWith("writing failed", errno);
      done += static_cast<std::size_t>(n);
    }
  }

  // Closes the file (flushed to disk first when `flush`) and renames it over the target.
  void Commit(bool flush) {
    if (flush && ::fsync(fd_) != 0) FailWith("flushing to disk failed", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) FailWith("closing failed", errno);
    if (std::rename(path_.c_str(), target_.c_str()) != 0) {
      FailWith("cannot replace it (renaming the temporary file failed)", errno);
    }
    committed_ = true;
  }

 private:
  void Create() {
    std::random_device random;
    for (int attempt = 0; attempt < 16; ++attempt) {
      path_ = FolderOf(target_) / ("." + target_.filename().string() + ".tmp-" +
                                   std::to_string(::getpid()) + "-" + std::to_string(random()));
      // 0666 so that the final file gets the usual permissions after the umask.
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd_ >= 0) return;
      if (errno != EEXIST) break;
    }
    committed_ = true;  // nothing of ours to remove
    const int error = errno;
    if (error == EACCES || error == EPERM || error == EROFS) {
      Fail(target_, "cannot write: the folder '" + FolderOf(target_).string() +
                        "' is not writable (" + ErrnoText(error) + "); choose another folder");
    }
    FailWith("cannot create a temporary file in its folder", error);
  }

  [[noreturn]] void FailWith(const std::string& what, int error) {
    Fail(target_, "cannot write: " + what + ": " + ErrnoText(error));
  }

  fs::path target_;
  fs::path path_;
  int fd_ = -1;
  bool committed_ = false;
};

std::string Line(const fs::path& file, const std::string& what) {
  std::string line = file.string() + ": " + what;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return line;
}

void Fail(const fs::path& file, const std::string& what) { throw MeshError(Line(file, what)); }

std::string ReadWholeFile(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (status.type() == fs::file_type::not_found) Fail(file, "no such file");
  if (ec) Fail(file, "cannot access: " + ec.message());
  if (status.type() == fs::file_type::directory) {
    Fail(file, "is a folder, not a mesh file; name a .stl, .obj or .ply file");
  }
  if (status.type() != fs::file_type::regular) Fail(file, "is not a regular file");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) Fail(file, "cannot get the file size: " + ec.message());
  if (size == 0) Fail(file, "the file is empty (0 bytes); export the mesh again");
  if (size > kMaxFileBytes) {
    Fail(file, "the file is too large (" + std::to_string(size) + " bytes, at most " +
                   std::to_string(kMaxFileBytes) + " are read); decimate the mesh");
  }
  std::FILE* stream = std::fopen(file.c_str(), "rb");
  if (stream == nullptr) {
    const int error = errno;
    Fail(file, "cannot open for reading: " + ErrnoText(error) +
                   (error == EACCES ? "; check the file's permissions" : ""));
  }
  std::string bytes(static_cast<std::size_t>(size), '\0');
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), stream);
  std::fclose(stream);
  if (got != bytes.size()) {
    Fail(file, "could read only " + std::to_string(got) + " of " + std::to_string(size) +
                   " bytes; is the file being written?");
  }
  return bytes;
}

}  // namespace occlude::io::detail

namespace occlude::io {

struct AtomicFileWriter::Temp {
  explicit Temp(const std::filesystem::path& target) : file(target) {}
  detail::TempFile file;
};

AtomicFileWriter::AtomicFileWriter(const std::filesystem::path& file, Durability durability)
    : durability_(durability) {
  if (file.filename().empty()) detail::Fail(file, "cannot write: the path names no file");
  const std::filesystem::path folder = detail::FolderOf(file);
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    detail::Fail(
        file, "cannot write: the folder '" + folder.string() + "' does not exist; create it first");
  }
  temp_ = std::make_unique<Temp>(file);
}

AtomicFileWriter::~AtomicFileWriter() = default;

void AtomicFileWriter::Append(std::string_view bytes) {
  temp_->file.WriteAt(size_, bytes);
  size_ += bytes.size();
}

void AtomicFileWriter::Overwrite(std::size_t offset, std::string_view bytes) {
  if (offset + bytes.size() > size_) {
    throw std::logic_error("AtomicFileWriter::Overwrite: past the bytes appended");
  }
  temp_->file.WriteAt(offset, bytes);
}

void AtomicFileWriter::Commit() { temp_->file.Commit(durability_ == Durability::kDurable); }

void WriteFileAtomically(const std::filesystem::path& file, const std::string& bytes,
                         Durability durability) {
  AtomicFileWriter writer(file, durability);
  writer.Append(bytes);
  writer.Commit();
}

}  // namespace occlude::io
