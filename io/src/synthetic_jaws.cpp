// MakeSyntheticJawPair: validates the options and runs the generator's stages (layout, grid,
// design heights, gap and contacts, slabs, invariant checks), then expresses the upper jaw in
// its own frame U. Why the bite cannot interpenetrate: see synthetic_gap.cpp.
#include "occlude/io/synthetic_jaws.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "synthetic_jaws_internal.h"

namespace occlude::io {
namespace {

void ValidateOptions(const SyntheticJawOptions& options) {
  if (options.triangles_per_jaw < kMinSyntheticTriangles ||
      options.triangles_per_jaw > kMaxSyntheticTriangles) {
    throw std::invalid_argument(
        "synthetic jaws: triangles_per_jaw = " + std::to_string(options.triangles_per_jaw) +
        " is outside " + std::to_string(kMinSyntheticTriangles) + ".." +
        std::to_string(kMaxSyntheticTriangles));
  }
}

/// Parts of one jaw (0 = gingiva/base, then its teeth in Universal order) and the part of every
/// grid vertex from its crown index (-1 = gingiva).
std::vector<std::int32_t> JawParts(const synthetic::JawLayout& jaw,
                                   const std::vector<int>& vertex_tooth, const char* which,
                                   std::vector<MeshPart>* parts) {
  parts->push_back({std::string("synthetic ") + which + " gingiva", 0});
  // jaw.teeth is sorted by s; Universal order runs with s (upper) or against it (lower).
  const int count = static_cast<int>(jaw.teeth.size());
  const bool ascending = count < 2 || jaw.teeth.front().number < jaw.teeth.back().number;
  std::vector<std::int32_t> part_of_tooth(jaw.teeth.size());
  for (int k = 0; k < count; ++k) {
    const int ordered = ascending ? k : count - 1 - k;
    const synthetic::Tooth& tooth = jaw.teeth[static_cast<std::size_t>(ordered)];
    part_of_tooth[static_cast<std::size_t>(ordered)] = static_cast<std::int32_t>(parts->size());
    parts->push_back({"synthetic tooth " + std::to_string(tooth.number), tooth.number});
  }
  std::vector<std::int32_t> vertex_part(vertex_tooth.size(), 0);
  for (std::size_t v = 0; v < vertex_tooth.size(); ++v) {
    if (vertex_tooth[v] >= 0) {
      vertex_part[v] = part_of_tooth[static_cast<std::size_t>(vertex_tooth[v])];
    }
  }
  return vertex_part;
}

std::vector<SyntheticContact> Contacts(const synthetic::DentitionLayout& layout,
                                       const synthetic::OcclusalGrid& grid,
                                       const synthetic::OcclusalFields& fields,
                                       const synthetic::GapResult& gap) {
  std::vector<SyntheticContact> contacts;
  for (const int c : gap.contact_vertex) {
    const auto v = static_cast<std::size_t>(c);
    SyntheticContact contact;
    contact.p_L = Eigen::Vector3d(grid.xz[v].x(), fields.lower_y[v], grid.xz[v].y());
    contact.upper_tooth =
        layout.upper.teeth[static_cast<std::size_t>(fields.upper_tooth[v])].number;
    contact.lower_tooth =
        layout.lower.teeth[static_cast<std::size_t>(fields.lower_tooth[v])].number;
    contacts.push_back(contact);
  }
  return contacts;
}

/// The landmarks of both jaws (upper ones moved into U) and the relationships they make.
void AddLandmarks(const synthetic::DentitionLayout& layout, const synthetic::OcclusalGrid& grid,
                  const std::vector<Eigen::Vector3i>& triangles,
                  const synthetic::OcclusalFields& fields, const synthetic::GapResult& gap,
                  SyntheticJawPair* pair) {
  const std::vector<Landmark> lower_L = synthetic::JawLandmarks(
      layout.lower, false, layout.arch, grid, triangles, fields.lower_y, fields.lower_tooth);
  std::vector<Landmark> upper = synthetic::JawLandmarks(layout.upper, true, layout.arch, grid,
                                                        triangles, gap.upper_y, fields.upper_tooth);
  pair->relationships = synthetic::DesignedRelationships(lower_L, upper);
  const Eigen::Isometry3d X_UL = pair->X_LU.inverse();
  for (Landmark& l : upper) l.p = X_UL * l.p;
  pair->landmarks = std::move(upper);
  pair->landmarks.insert(pair->landmarks.end(), lower_L.begin(), lower_L.end());
}

}  // namespace

SyntheticJawPair MakeSyntheticJawPair(const SyntheticJawOptions& options) {
  ValidateOptions(options);
  const synthetic::DentitionLayout layout = synthetic::MakeDentitionLayout(options.seed);
  const synthetic::OcclusalGrid grid =
      synthetic::MakeOcclusalGrid(layout, options.triangles_per_jaw);
  const synthetic::OcclusalFields fields = synthetic::SampleFields(layout, grid);
  const std::vector<Eigen::Vector3i> triangles = synthetic::OcclusalTriangles(grid, fields.lower_y);
  const synthetic::GapResult gap = synthetic::MakeUpperSurface(layout, grid, fields, triangles);

  std::vector<MeshPart> lower_parts, upper_parts;
  const auto lower_vertex_part = JawParts(layout.lower, fields.lower_tooth, "lower", &lower_parts);
  const auto upper_vertex_part = JawParts(layout.upper, fields.upper_tooth, "upper", &upper_parts);
  SyntheticJawPair pair;
  pair.lower_L =
      synthetic::MakeSlab(grid, triangles, fields.lower_y, layout.lower_base_y,
                          /*occlusal_faces_up=*/true, lower_vertex_part, std::move(lower_parts));
  const TriangleMesh upper_L =
      synthetic::MakeSlab(grid, triangles, gap.upper_y, layout.upper_top_y,
                          /*occlusal_faces_up=*/false, upper_vertex_part, std::move(upper_parts));
  const std::string broken = synthetic::CheckInvariants(grid, fields, gap, pair.lower_L, upper_L,
                                                        options.triangles_per_jaw);
  if (!broken.empty()) throw std::logic_error("synthetic jaws: internal invariant: " + broken);

  pair.X_LU = Eigen::Isometry3d(Eigen::Translation3d(0.0, layout.upper_origin_y, 0.0));
  pair.upper_U = upper_L.Transformed(pair.X_LU.inverse());
  pair.contacts = Contacts(layout, grid, fields, gap);
  pair.occlusal_axis_L = Eigen::Vector3d::UnitY();
  AddLandmarks(layout, grid, triangles, fields, gap, &pair);
  pair.class2_shift_L = Eigen::Vector3d(0.0, 0.0, synthetic::kClass2ShiftMm);
  return pair;
}

}  // namespace occlude::io
