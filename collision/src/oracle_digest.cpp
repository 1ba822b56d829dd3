// HashOracleResult: an oracle answer's every value into a content hash (oracle.h).
#include "occlude/collision/oracle.h"

namespace occlude::collision {
namespace {

void HashPoints(const std::vector<SurfacePoint>& points, io::Hasher64* h) {
  h->AddValue(static_cast<std::uint64_t>(points.size()));
  for (const SurfacePoint& p : points) {
    for (int a = 0; a < 3; ++a) h->AddValue(p.p_L[a]);
    h->AddValue(p.distance_mm);
    h->AddValue(p.area_mm2);
    h->AddValue(p.part);
  }
}

}  // namespace

void HashOracleResult(const OracleResult& r, io::Hasher64* h) {
  for (const double v :
       {r.max_penetration_mm, r.penetration_area_mm2, r.contact_area_mm2, r.min_distance_mm,
        r.left_share, r.right_share, r.anterior_share, r.posterior_share, r.deepest_p_L.x(),
        r.deepest_p_L.y(), r.deepest_p_L.z()}) {
    h->AddValue(v);
  }
  for (const std::size_t n : {r.deep_samples, r.contact_samples, r.cells, r.samples_evaluated})
    h->AddValue(static_cast<std::uint64_t>(n));
  for (const PartTotals& p : r.parts) {
    h->AddValue(p.contact_area_mm2);
    h->AddValue(p.penetration_area_mm2);
    h->AddValue(p.max_penetration_mm);
    h->AddValue(static_cast<std::uint64_t>(p.contact_samples));
  }
  HashPoints(r.contacts, h);
  HashPoints(r.penetrations, h);
  for (const DistanceResidual& res : r.residuals) {
    h->AddValue(res.distance_mm);
    for (int i = 0; i < 6; ++i) h->AddValue(res.gradient[i]);
    h->AddValue(res.area_mm2);
  }
}

}  // namespace occlude::collision
