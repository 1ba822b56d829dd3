// OracleCodec: every member of the structures a JawOracle builds, written in a fixed order and
// read back in the same order, with the sizes the structures rely on checked on the way in.
#include "oracle_codec.h"

#include <utility>

namespace occlude::collision::detail {
namespace {

void PutGrid(const VoxelGrid& g, ByteWriter* out) {
  out->Value(g.voxel_size_mm);
  out->Value(g.origin_F);
  out->Value(g.dims);
  out->Array(g.surface_keys);
  out->Array(g.triangle_offsets);
  out->Array(g.triangle_indices);
  out->Array(g.proximity_keys);
  out->Array(g.interior_runs);
}

void GetGrid(ByteReader* in, std::size_t triangles, VoxelGrid* g) {
  g->voxel_size_mm = in->Value<double>();
  g->origin_F = in->Value<Eigen::Vector3d>();
  g->dims = in->Value<Eigen::Vector3i>();
  in->Array(&g->surface_keys);
  in->ArrayOf(g->surface_keys.size() + 1, &g->triangle_offsets);
  in->ArrayOf(g->triangle_offsets.back(), &g->triangle_indices);
  in->Array(&g->proximity_keys);
  in->Array(&g->interior_runs);
  for (const std::uint32_t t : g->triangle_indices) in->Check(t < triangles, "triangle index");
}

void PutOctree(const Octree& o, ByteWriter* out) {
  out->Value(o.top_level);
  out->Array(o.level_begin);
  out->Array(o.level_end);
  out->Array(o.coord);
  out->Array(o.first_child);
  out->Array(o.child_mask);
}

void GetOctree(ByteReader* in, std::size_t leaves, Octree* o) {
  o->top_level = in->Value<int>();
  in->ArrayOf(static_cast<std::size_t>(o->top_level + 1), &o->level_begin);
  in->ArrayOf(o->level_begin.size(), &o->level_end);
  in->Array(&o->coord);
  in->ArrayOf(o->coord.size(), &o->first_child);
  in->ArrayOf(o->coord.size(), &o->child_mask);
  in->Check(o->num_leaves() == leaves, "octree leaves differ from the surface voxels");
}

void PutExplicit(const ExplicitSpheres& e, ByteWriter* out) {
  out->Value(static_cast<std::int32_t>(e.from));
  out->Array(e.nodes);
  out->Array(e.compact);
}

void GetExplicit(ByteReader* in, std::size_t nodes, ExplicitSpheres* e) {
  e->from = static_cast<SphereMode>(in->Value<std::int32_t>());
  in->Array(&e->nodes);
  in->Check(e->nodes.empty() || e->nodes.size() == nodes, "explicit spheres per node");
  in->ArrayOf(e->nodes.size(), &e->compact);
}

void PutStats(const SphereTreeStats& s, ByteWriter* out) {
  out->Value(s.voxelize);
  out->Array(s.levels);
  for (const std::size_t n : {s.nodes, s.leaves, s.bytes_grid, s.bytes_octree, s.bytes_explicit,
                              s.bytes_mesh, s.bytes_bound}) {
    out->Value(static_cast<std::uint64_t>(n));
  }
  for (const double t : {s.seconds_voxelize, s.seconds_octree, s.seconds_explicit, s.seconds_bound})
    out->Value(t);
}

void GetStats(ByteReader* in, SphereTreeStats* s) {
  s->voxelize = in->Value<VoxelizeStats>();
  in->Array(&s->levels);
  for (std::size_t* n : {&s->nodes, &s->leaves, &s->bytes_grid, &s->bytes_octree,
                         &s->bytes_explicit, &s->bytes_mesh, &s->bytes_bound}) {
    *n = static_cast<std::size_t>(in->Value<std::uint64_t>());
  }
  for (double* t :
       {&s->seconds_voxelize, &s->seconds_octree, &s->seconds_explicit, &s->seconds_bound}) {
    *t = in->Value<double>();
  }
}

void PutArch(const ArchFrame& a, ByteWriter* out) {
  for (const Eigen::Vector3d& v : {a.origin_L, a.occlusal_L, a.anterior_L, a.lateral_L})
    out->Value(v);
  out->Value(a.anterior_split_mm);
}

void GetArch(ByteReader* in, ArchFrame* a) {
  for (Eigen::Vector3d* v : {&a->origin_L, &a->occlusal_L, &a->anterior_L, &a->lateral_L})
    *v = in->Value<Eigen::Vector3d>();
  a->anterior_split_mm = in->Value<double>();
}

}  // namespace

void OracleCodec::Put(const KeyIndexHash& hash, ByteWriter* out) {
  out->Array(hash.slots_);
  out->Value(static_cast<std::uint64_t>(hash.mask_));
  out->Value(static_cast<std::uint64_t>(hash.size_));
}

void OracleCodec::Get(ByteReader* in, KeyIndexHash* hash) {
  in->Array(&hash->slots_);
  hash->mask_ = static_cast<std::size_t>(in->Value<std::uint64_t>());
  hash->size_ = static_cast<std::size_t>(in->Value<std::uint64_t>());
  // Find probes slots_[i & mask_] and stops at an empty slot, which a 3/4 load guarantees.
  const std::size_t n = hash->slots_.size();
  in->Check(n == 0 || ((n & (n - 1)) == 0 && hash->mask_ == n - 1 && 4 * hash->size_ <= 3 * n),
            "hash table shape");
}

void OracleCodec::Put(const BrickSet& set, ByteWriter* out) {
  out->Array(set.bricks_);
  Put(set.index_, out);
  out->Value(static_cast<std::uint64_t>(set.voxels_));
  out->Array(set.dense_);
  for (int a = 0; a < 3; ++a) out->Value(set.dense_lo_[a]);
  for (int a = 0; a < 3; ++a) out->Value(set.dense_dims_[a]);
}

void OracleCodec::Get(ByteReader* in, BrickSet* set) {
  in->Array(&set->bricks_);
  Get(in, &set->index_);
  set->voxels_ = static_cast<std::size_t>(in->Value<std::uint64_t>());
  in->Array(&set->dense_);
  for (int a = 0; a < 3; ++a) set->dense_lo_[a] = in->Value<std::uint32_t>();
  for (int a = 0; a < 3; ++a) set->dense_dims_[a] = in->Value<std::uint32_t>();
  in->Check(set->dense_.size() ==
                std::size_t{set->dense_dims_[0]} * set->dense_dims_[1] * set->dense_dims_[2],
            "dense brick index size");
  for (const std::uint32_t i : set->dense_)
    in->Check(i == KeyIndexHash::kNotFound || i < set->bricks_.size(), "dense brick index");
}

void OracleCodec::Put(const PseudoNormals& n, ByteWriter* out) {
  out->Array(n.faces_);
  out->Array(n.edges_);
  out->Array(n.vertices_);
  out->Array(n.corners_);
  out->Bools(n.boundary_edge_);
  out->Bools(n.boundary_vertex_);
}

void OracleCodec::Get(ByteReader* in, PseudoNormals* n) {
  in->Array(&n->faces_);
  in->ArrayOf(3 * n->faces_.size(), &n->edges_);
  in->Array(&n->vertices_);
  in->ArrayOf(n->faces_.size(), &n->corners_);
  in->Bools(&n->boundary_edge_);
  in->Check(n->boundary_edge_.size() == n->edges_.size(), "boundary edges");
  in->Bools(&n->boundary_vertex_);
  in->Check(n->boundary_vertex_.size() == n->vertices_.size(), "boundary vertices");
}

void OracleCodec::Put(const DistanceBound::Level& l, ByteWriter* out) {
  for (const double v : {l.s, l.inv_s, l.s2, l.scale, l.cap_mm}) out->Value(v);
  out->Value(l.shift);
  out->Value(l.cap);
  out->Value(l.m_mm);
  out->Array(l.bricks);
  Put(l.index, out);
  out->Array(l.table);
  out->Value(l.table_lo);
  out->Value(l.table_dims);
}

void OracleCodec::Get(ByteReader* in, DistanceBound::Level* l) {
  for (double* v : {&l->s, &l->inv_s, &l->s2, &l->scale, &l->cap_mm}) *v = in->Value<double>();
  l->shift = in->Value<int>();
  l->cap = in->Value<std::uint8_t>();
  l->m_mm = in->Value<std::array<double, 256>>();
  in->Array(&l->bricks);
  Get(in, &l->index);
  in->Array(&l->table);
  l->table_lo = in->Value<Eigen::Vector3i>();
  l->table_dims = in->Value<Eigen::Vector3i>();
  in->Check(l->table.empty() || l->table.size() == static_cast<std::size_t>(l->table_dims.prod()),
            "bound brick table size");
  for (const std::uint32_t i : l->table)
    in->Check(i == KeyIndexHash::kNotFound || i < l->bricks.size(), "bound brick table");
}

void OracleCodec::Put(const DistanceBound& bound, ByteWriter* out) {
  out->Value(bound.origin_);
  out->Value(bound.finest_level_);
  out->Value(static_cast<std::uint64_t>(bound.levels_.size()));
  for (const DistanceBound::Level& l : bound.levels_) Put(l, out);
}

void OracleCodec::Get(ByteReader* in, DistanceBound* bound) {
  bound->origin_ = in->Value<Eigen::Vector3d>();
  bound->finest_level_ = in->Value<int>();
  const auto levels = in->Value<std::uint64_t>();
  in->Check(levels <= 21, "bound levels");
  bound->levels_.resize(static_cast<std::size_t>(levels));
  for (DistanceBound::Level& l : bound->levels_) Get(in, &l);
}

void OracleCodec::Put(const SphereTree& tree, ByteWriter* out) {
  PutGrid(tree.grid_, out);
  PutOctree(tree.octree_, out);
  PutExplicit(tree.explicit_, out);
  Put(tree.bound_, out);
  PutStats(tree.stats_, out);
}

// tree->mesh_ is set (the mesh the key was checked against).
void OracleCodec::Get(ByteReader* in, SphereTree* tree) {
  GetGrid(in, tree->mesh_->num_triangles(), &tree->grid_);
  GetOctree(in, tree->grid_.num_surface(), &tree->octree_);
  GetExplicit(in, tree->octree_.num_nodes(), &tree->explicit_);
  Get(in, &tree->bound_);
  GetStats(in, &tree->stats_);
}

void OracleCodec::Put(const NarrowBandSdf& sdf, ByteWriter* out) {
  Put(sdf.normals_, out);
  std::vector<double> packed;  // a, b, c, center (x, y, z each), radius per triangle
  packed.reserve(13 * sdf.packed_.size());
  for (const NarrowBandSdf::PackedTriangle& t : sdf.packed_) {
    for (const Eigen::Vector3d* v : {&t.a, &t.b, &t.c, &t.center})
      packed.insert(packed.end(), v->data(), v->data() + 3);
    packed.push_back(t.radius);
  }
  out->Array(packed);
  out->Array(sdf.original_);
  for (const double v : {sdf.s_, sdf.inv_s_, sdf.band_mm_, sdf.build_seconds_}) out->Value(v);
  out->Value(sdf.origin_);
  out->Value(sdf.dims_);
  out->Value(sdf.shift_);
  out->Array(sdf.tri_offsets_);
  out->Array(sdf.tri_indices_);
  Put(sdf.surface_, out);
  Put(sdf.band_, out);
  out->Array(sdf.corner_bricks_);
}

// sdf->mesh_ is set (the mesh the key was checked against).
void OracleCodec::Get(ByteReader* in, NarrowBandSdf* sdf) {
  Get(in, &sdf->normals_);
  const std::size_t triangles = sdf->mesh_->num_triangles();
  std::vector<double> packed;
  in->ArrayOf(13 * triangles, &packed);
  sdf->packed_.resize(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const double* p = packed.data() + 13 * t;
    NarrowBandSdf::PackedTriangle& out = sdf->packed_[t];
    out.a = Eigen::Vector3d(p[0], p[1], p[2]);
    out.b = Eigen::Vector3d(p[3], p[4], p[5]);
    out.c = Eigen::Vector3d(p[6], p[7], p[8]);
    out.center = Eigen::Vector3d(p[9], p[10], p[11]);
    out.radius = p[12];
  }
  in->ArrayOf(triangles, &sdf->original_);
  for (double* v : {&sdf->s_, &sdf->inv_s_, &sdf->band_mm_, &sdf->build_seconds_})
    *v = in->Value<double>();
  sdf->origin_ = in->Value<Eigen::Vector3d>();
  sdf->dims_ = in->Value<Eigen::Vector3i>();
  sdf->shift_ = in->Value<int>();
  in->Array(&sdf->tri_offsets_);
  in->Check(!sdf->tri_offsets_.empty(), "triangle lists");
  in->ArrayOf(sdf->tri_offsets_.back(), &sdf->tri_indices_);
  for (const std::uint32_t t : sdf->tri_indices_) in->Check(t < triangles, "triangle index");
  Get(in, &sdf->surface_);
  Get(in, &sdf->band_);
  in->ArrayOf(sdf->band_.bricks().size(), &sdf->corner_bricks_);
}

void OracleCodec::PutArrays(const JawOracle& o, ByteWriter* out) {
  PutArch(o.arch_, out);
  out->Array(o.sample_p_U_);
  out->Array(o.sample_offset_U_);
  out->Array(o.sample_area_);
  out->Array(o.sample_part_);
  out->Array(o.voxel_sample_begin_);
  out->Array(o.voxel_centroid_U_);
  out->Array(o.voxel_area_);
  out->Array(o.voxel_sphere_U_);
  out->Array(o.voxel_part_);
  out->Array(o.node_leaf_begin_);
  out->Array(o.node_leaf_end_);
  out->Array(o.cell_center_U_);
  out->Array(o.cell_radius_);
  out->Array(o.node_sample_sphere_U_);
  out->Array(o.component_samples_);
  out->Array(o.interior_row_begin_);
  out->Value(o.samples_centre_U_);
  out->Value(o.samples_radius_);
  out->Bools(o.part_is_anterior_tooth_);
  out->Bools(o.part_has_tooth_);
  out->Value(o.build_seconds_);
}

// The trees are read (their sizes are checked against here).
void OracleCodec::GetArrays(ByteReader* in, JawOracle* o) {
  const std::size_t voxels = o->upper_.grid().num_surface(), nodes = o->upper_.octree().num_nodes();
  GetArch(in, &o->arch_);
  in->Array(&o->sample_p_U_);
  const std::size_t samples = o->sample_p_U_.size();
  in->ArrayOf(samples, &o->sample_offset_U_);
  in->ArrayOf(samples, &o->sample_area_);
  in->ArrayOf(samples, &o->sample_part_);
  in->ArrayOf(voxels + 1, &o->voxel_sample_begin_);
  in->Check(o->voxel_sample_begin_.back() == samples, "samples per voxel");
  in->ArrayOf(voxels, &o->voxel_centroid_U_);
  in->ArrayOf(voxels, &o->voxel_area_);
  in->ArrayOf(voxels, &o->voxel_sphere_U_);
  in->ArrayOf(voxels, &o->voxel_part_);
  in->ArrayOf(nodes, &o->node_leaf_begin_);
  in->ArrayOf(nodes, &o->node_leaf_end_);
  in->Array(&o->cell_center_U_);
  in->ArrayOf(o->cell_center_U_.size(), &o->cell_radius_);
  in->Array(&o->node_sample_sphere_U_);
  in->Check(o->node_sample_sphere_U_.size() <= nodes, "node sample spheres");
  in->Array(&o->component_samples_);
  in->Array(&o->interior_row_begin_);
  o->BoundInterior();
  o->samples_centre_U_ = in->Value<Eigen::Vector3d>();
  o->samples_radius_ = in->Value<double>();
  in->Bools(&o->part_is_anterior_tooth_);
  in->Bools(&o->part_has_tooth_);
  o->build_seconds_ = in->Value<double>();
}

const std::vector<std::string>& OracleCodec::Tags() {
  static const std::vector<std::string> kTags = {"lowr", "uppr", "lsdf", "fbnd", "orcl"};
  return kTags;
}

void OracleCodec::PutSection(const JawOracle& o, std::size_t index, ByteWriter* out) {
  switch (index) {
    case 0:
      return Put(o.lower_, out);
    case 1:
      return Put(o.upper_, out);
    case 2:
      return Put(o.sdf_, out);
    case 3:
      return Put(o.field_bound_, out);
    default:
      return PutArrays(o, out);
  }
}

JawOracle OracleCodec::Assemble(const std::vector<std::string_view>& sections,
                                std::shared_ptr<const io::TriangleMesh> lower_L,
                                std::shared_ptr<const io::TriangleMesh> upper_U,
                                const OracleOptions& options, const ReleaseBytes* release) {
  JawOracle o;
  o.options_ = options;
  o.lower_.mesh_ = lower_L;
  o.upper_.mesh_ = std::move(upper_U);
  o.sdf_.mesh_ = std::move(lower_L);
  std::vector<ByteReader> in;
  for (std::size_t i = 0; i < Tags().size(); ++i) in.emplace_back(sections[i], Tags()[i], release);
  Get(&in[0], &o.lower_);
  Get(&in[1], &o.upper_);
  Get(&in[2], &o.sdf_);
  Get(&in[3], &o.field_bound_);
  GetArrays(&in[4], &o);
  for (const ByteReader& r : in) r.Check(r.done(), "bytes left over at the end");
  return o;
}

}  // namespace occlude::collision::detail
