// Occlusal-axis sweep (see sweep.h).
#include "bench/sweep.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace occlude::app {

std::vector<SweepRow> RunSweep(const collision::CollisionPair& pair,
                               const Eigen::Isometry3d& X_LU_ref, const SweepOptions& options) {
  std::vector<SweepRow> rows;
  collision::CollisionResult res;
  for (const double offset : options.offsets_mm) {
    const Eigen::Isometry3d X_LU = Eigen::Translation3d(offset * options.axis_L) * X_LU_ref;
    for (const auto mode : options.modes) {
      SweepRow row;
      row.offset_mm = offset;
      row.mode = mode;
      collision::CollisionRequest req;
      req.spheres = mode;
      req.first_only = true;
      row.boolean_us = TimeMicros([&] { pair.Query(X_LU, req, &res); }, options.reps);
      row.overlap = res.overlap;
      row.boolean_tests = res.node_tests;
      req.first_only = false;
      req.delta_mm = options.delta_mm;
      row.pairs_us =
          TimeMicros([&] { pair.Query(X_LU, req, &res); }, std::max(1, options.reps / 3));
      row.pairs = res.pairs.size();
      row.pairs_tests = res.node_tests;
      if (options.exact && mode == collision::SphereMode::kExplicit) {
        req.exact = true;
        row.exact_us =
            TimeMicros([&] { pair.Query(X_LU, req, &res); }, std::max(1, options.reps / 10));
        row.has_exact = true;
        row.contacts = res.contacts.size();
        row.min_distance_mm = res.min_distance_mm;
        row.intersect = res.triangles_intersect;
      }
      rows.push_back(row);
    }
  }
  return rows;
}

std::string SweepTable(const std::vector<SweepRow>& rows) {
  std::ostringstream t;
  t << " offset  mode       overlap  bool_us  bool_tests     pairs  pairs_us  pair_tests  contacts "
       " "
       "min_dist  exact_us\n";
  for (const SweepRow& r : rows) {
    char dist[32] = "-";
    char exact[32] = "-";
    char contacts[32] = "-";
    if (r.has_exact) {
      if (std::isfinite(r.min_distance_mm)) {
        std::snprintf(dist, sizeof dist, "%.4f", r.min_distance_mm);
      } else {
        std::snprintf(dist, sizeof dist, "> delta");
      }
      std::snprintf(exact, sizeof exact, "%.1f", r.exact_us.median);
      std::snprintf(contacts, sizeof contacts, "%zu", r.contacts);
    }
    char line[256];
    std::snprintf(
        line, sizeof line, "%+7.2f  %-9s  %-7s %8.1f  %10zu  %8zu %9.1f  %10zu  %8s  %8s  %8s\n",
        r.offset_mm, collision::ToString(r.mode), r.overlap ? "yes" : "no", r.boolean_us.median,
        r.boolean_tests, r.pairs, r.pairs_us.median, r.pairs_tests, contacts, dist, exact);
    t << line;
  }
  return t.str();
}

std::string SweepJson(const std::vector<SweepRow>& rows) {
  std::ostringstream j;
  j << "[";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const SweepRow& r = rows[i];
    j << (i ? ",\n    " : "\n    ") << "{\"offset_mm\": " << r.offset_mm << ", \"mode\": \""
      << collision::ToString(r.mode) << "\", \"overlap\": " << (r.overlap ? "true" : "false")
      << ", \"boolean_median_us\": " << r.boolean_us.median
      << ", \"boolean_max_us\": " << r.boolean_us.max
      << ", \"boolean_node_tests\": " << r.boolean_tests << ", \"voxel_pairs\": " << r.pairs
      << ", \"pairs_median_us\": " << r.pairs_us.median
      << ", \"pairs_node_tests\": " << r.pairs_tests;
    if (r.has_exact) {
      j << ", \"exact_contacts\": " << r.contacts << ", \"min_distance_mm\": "
        << (std::isfinite(r.min_distance_mm) ? std::to_string(r.min_distance_mm) : "null")
        << ", \"triangles_intersect\": " << (r.intersect ? "true" : "false")
        << ", \"exact_median_us\": " << r.exact_us.median;
    }
    j << "}";
  }
  j << "\n  ]";
  return j.str();
}

}  // namespace occlude::app
