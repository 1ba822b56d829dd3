// Private to occlude::collision: OracleCodec, the friend of the built structures that turns a
// JawOracle into the sections of a saved oracle and back (oracle_file.h has the format; the
// framing, checksums and key are in oracle_file.cpp, the structures in oracle_codec.cpp).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "byte_stream.h"
#include "occlude/collision/oracle.h"

namespace occlude::collision::detail {

struct OracleCodec {
  /// The sections' tags, in file order.
  static const std::vector<std::string>& Tags();
  /// The payload of section `index` (of Tags()).
  static void PutSection(const JawOracle& oracle, std::size_t index, ByteWriter* out);
  /// The oracle of the sections' payloads (one per tag) over these meshes; `options` are the
  /// ones the key was checked against; `release` (optional) is told of every array's bytes
  /// once copied. Throws OracleFileError(kCorrupt).
  static JawOracle Assemble(const std::vector<std::string_view>& sections,
                            std::shared_ptr<const io::TriangleMesh> lower_L,
                            std::shared_ptr<const io::TriangleMesh> upper_U,
                            const OracleOptions& options, const ReleaseBytes* release = nullptr);
  static const OracleOptions& Options(const JawOracle& oracle) { return oracle.options_; }

  static void Put(const SphereTree& tree, ByteWriter* out);
  static void Get(ByteReader* in, SphereTree* tree);
  static void Put(const NarrowBandSdf& sdf, ByteWriter* out);
  static void Get(ByteReader* in, NarrowBandSdf* sdf);
  static void Put(const DistanceBound& bound, ByteWriter* out);
  static void Get(ByteReader* in, DistanceBound* bound);
  static void Put(const DistanceBound::Level& level, ByteWriter* out);
  static void Get(ByteReader* in, DistanceBound::Level* level);
  static void Put(const KeyIndexHash& hash, ByteWriter* out);
  static void Get(ByteReader* in, KeyIndexHash* hash);
  static void Put(const BrickSet& set, ByteWriter* out);
  static void Get(ByteReader* in, BrickSet* set);
  static void Put(const PseudoNormals& normals, ByteWriter* out);
  static void Get(ByteReader* in, PseudoNormals* normals);
  /// The oracle's own arrays (samples, culling spheres, arch frame, per-part flags).
  static void PutArrays(const JawOracle& oracle, ByteWriter* out);
  static void GetArrays(ByteReader* in, JawOracle* oracle);
};

}  // namespace occlude::collision::detail
