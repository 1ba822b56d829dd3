// Atomic whole-file writes (io/atomic_file.h): the file appears only on Commit, whole (also in
// pieces larger than one write call); a writer dropped uncommitted leaves no file and no
// temporary one; Overwrite patches appended bytes and refuses bytes not yet appended; a missing
// folder is one error naming the file.
#include "occlude/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::io {
namespace {

std::string Read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t FilesIn(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFileWriterTest, TheFileAppearsWholeOnCommitWithItsHeaderPatched) {
  const test::TempDir dir;
  const std::filesystem::path file = dir / "entry.bin";
  {
    AtomicFileWriter out(file);
    out.Append("HEAD");
    out.Append("payload-1,");
    out.Append("payload-2");
    EXPECT_FALSE(std::filesystem::exists(file));  // only the temporary file so far
    out.Overwrite(0, "head");
    out.Overwrite(12, "PA");
    out.Commit();
  }
  EXPECT_EQ(Read(file), "headpayload-PApayload-2");
  EXPECT_EQ(FilesIn(dir.path()), 1u);
}

// Pieces larger than one write call (1 MiB) land whole, byte for byte, appended and patched
// across a call's boundary; WriteFileAtomically likewise, flushed to disk or not.
TEST(AtomicFileWriterTest, PiecesOfSeveralMegabytesLandByteForByte) {
  const test::TempDir dir;
  std::string big(3 * (std::size_t{1} << 20) + 12345, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>((i * 131 + i / 7) & 0xff);
  const std::filesystem::path file = dir / "big.bin";
  {
    AtomicFileWriter out(file);
    out.Append("HEAD");
    out.Append(big);
    out.Append(big.substr(0, 1000));
    const std::string patch(5000, 'p');
    out.Overwrite((std::size_t{1} << 20) - 2000, patch);  // across the first call's end
    out.Commit();
  }
  std::string want = "HEAD" + big + big.substr(0, 1000);
  want.replace((std::size_t{1} << 20) - 2000, 5000, std::string(5000, 'p'));
  EXPECT_EQ(Read(file), want);
  WriteFileAtomically(dir / "whole.bin", big);
  EXPECT_EQ(Read(dir / "whole.bin"), big);
  // Unflushed (the caches' writes): the same bytes, renamed in place, no temporary file left.
  WriteFileAtomically(dir / "cache.bin", big, Durability::kAtomicOnly);
  EXPECT_EQ(Read(dir / "cache.bin"), big);
  {
    AtomicFileWriter out(dir / "cache-pieces.bin", Durability::kAtomicOnly);
    out.Append(big.substr(0, 100));
    out.Append(big.substr(100));
    out.Overwrite(0, "HEAD");
    out.Commit();
  }
  EXPECT_EQ(Read(dir / "cache-pieces.bin"), "HEAD" + big.substr(4));
  EXPECT_EQ(FilesIn(dir.path()), 4u);
}

TEST(AtomicFileWriterTest, DroppedUncommittedItLeavesNothingAndTheOldFileStays) {
  const test::TempDir dir;
  const std::filesystem::path file = dir / "entry.bin";
  WriteFileAtomically(file, "old");
  {
    AtomicFileWriter out(file);
    out.Append("new bytes that never land");
  }
  EXPECT_EQ(Read(file), "old");
  EXPECT_EQ(FilesIn(dir.path()), 1u);
}

TEST(AtomicFileWriterTest, OverwritePastTheAppendedBytesIsRefused) {
  const test::TempDir dir;
  AtomicFileWriter out(dir / "entry.bin");
  out.Append("abc");
  EXPECT_THROW(out.Overwrite(2, "xy"), std::logic_error);
  EXPECT_NO_THROW(out.Overwrite(1, "xy"));
}

TEST(AtomicFileWriterTest, AMissingFolderIsOneErrorNamingTheFile) {
  const test::TempDir dir;
  try {
    AtomicFileWriter out(dir / "no-such-folder" / "entry.bin");
    ADD_FAILURE() << "no error";
  } catch (const MeshError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("entry.bin"), std::string::npos) << what;
    EXPECT_NE(what.find("does not exist"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace occlude::io
