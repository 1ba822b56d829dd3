// Hasher64 (four lanes of multiply-rotate rounds over 8-byte words, a chained avalanche fold)
// and the content hash of a TriangleMesh.
#include "occlude/io/content_hash.h"

#include <cstring>

namespace occlude::io {
namespace {

// Odd multipliers (drawn at random once; any odd constants with well-spread bits do).
constexpr std::uint64_t kWordMul = 0x7d81d544bb08d0ddULL;
constexpr std::uint64_t kLaneMul = 0x5a486531020173e1ULL;
constexpr std::uint64_t kLengthMul = 0x3440b0841534f73bULL;
constexpr std::uint64_t kLaneSeed = 0x2c21a4b6c51a1991ULL;

std::uint64_t Rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

std::uint64_t Load64(const unsigned char* p) {
  std::uint64_t w;
  std::memcpy(&w, p, sizeof w);
  return w;
}

// One round: a bijection of the lane for a fixed word and of the word for a fixed lane.
std::uint64_t Round(std::uint64_t lane, std::uint64_t word) {
  return Rotl(lane ^ (word * kWordMul), 29) * kLaneMul;
}

}  // namespace

Hasher64::Hasher64(std::uint64_t seed) : seed_(seed) {
  for (std::size_t i = 0; i < lane_.size(); ++i) lane_[i] = Mix64(seed + (i + 1) * kLaneSeed);
}

void Hasher64::Stripe(const unsigned char* p) {
  lane_[0] = Round(lane_[0], Load64(p));
  lane_[1] = Round(lane_[1], Load64(p + 8));
  lane_[2] = Round(lane_[2], Load64(p + 16));
  lane_[3] = Round(lane_[3], Load64(p + 24));
}

void Hasher64::Add(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  length_ += size;
  if (pending_size_ > 0) {
    const std::size_t take = std::min(size, pending_.size() - pending_size_);
    std::memcpy(pending_.data() + pending_size_, p, take);
    pending_size_ += take;
    p += take;
    size -= take;
    if (pending_size_ < pending_.size()) return;
    Stripe(pending_.data());
    pending_size_ = 0;
  }
  for (; size >= pending_.size(); p += pending_.size(), size -= pending_.size()) Stripe(p);
  if (size > 0) std::memcpy(pending_.data(), p, size);
  pending_size_ = size;
}

void Hasher64::AddString(std::string_view text) {
  AddValue(static_cast<std::uint64_t>(text.size()));
  Add(text.data(), text.size());
}

std::uint64_t Hasher64::Finish() const {
  std::array<std::uint64_t, 4> lane = lane_;
  if (pending_size_ > 0) {  // the last partial stripe, zero-padded (the length tells it apart)
    std::array<unsigned char, 32> last{};
    std::memcpy(last.data(), pending_.data(), pending_size_);
    for (std::size_t i = 0; i < lane.size(); ++i) lane[i] = Round(lane[i], Load64(&last[8 * i]));
  }
  // Chained: a bijection of each lane for fixed others, so a lane that differs always shows.
  std::uint64_t h = Mix64(seed_ ^ (length_ * kLengthMul));
  for (const std::uint64_t l : lane) h = Mix64(h ^ l);
  return h;
}

std::uint64_t Hash64(const void* data, std::size_t size, std::uint64_t seed) {
  Hasher64 h(seed);
  h.Add(data, size);
  return h.Finish();
}

std::uint64_t MeshContentHash(const TriangleMesh& mesh) {
  Hasher64 h;
  h.AddString("occlude::io::TriangleMesh");
  h.AddArray(mesh.vertices);
  h.AddArray(mesh.triangles);
  h.AddArray(mesh.face_normals);
  h.AddArray(mesh.triangle_part);
  h.AddValue(static_cast<std::uint64_t>(mesh.parts.size()));
  for (const MeshPart& part : mesh.parts) {
    h.AddString(part.name);
    h.AddValue(static_cast<std::int64_t>(part.tooth_number));
  }
  return h.Finish();
}

std::string HashHex(std::uint64_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) out[static_cast<std::size_t>(i)] = kDigits[value & 15];
  return out;
}

}  // namespace occlude::io
