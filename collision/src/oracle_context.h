// Per-query state of JawOracle::Query shared by its two source files: the
// constants of one query and what the cell test found out about the current
// cell, so that the evaluation can cull the cell's voxels with the same
// arguments (oracle_query.cpp tests cells, oracle_evaluate.cpp their voxels
// and samples).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "occlude/collision/oracle.h"
#include "occlude/collision/sdf_sampler.h"
#include "occlude/collision/sphere_table.h"
#include "voxelize_detail.h"

namespace occlude::collision {

/// Where the unknown samples of a cell (outside the field's band) lie.
enum class UnknownSide {
  kExterior,       ///< all outside the lower jaw: they count for nothing
  kMaybeInterior,  ///< classify each (only those inside the lower count, as deep)
  kInterior,       ///< all inside the lower jaw beyond the band: each counts as deep
};

struct JawOracle::QueryContext {
  static constexpr double kSqrt3 = 1.7320508075688772;
  static constexpr double kSlackMm = 1e-6;  ///< float rounding of stored values and offsets

  const Eigen::Isometry3d& X_LU;
  const OracleRequest& request;
  SdfSampler sampler;
  Eigen::Matrix4f M;  ///< U offsets (mm) -> L voxel units of the field: R_LU / s (top-left 3x3)
  Eigen::Matrix3d A;  ///< p_U -> the field's voxel coordinates of X_LU p_U: A p_U + b
  Eigen::Vector3d b;
  double outer;         ///< samples above this distance count for nothing but the minimum
  float outer_float;    ///< the smallest float >= outer (a float above it is above outer)
  double s;             ///< voxel size of the field
  double band_mm;       ///< the field's band
  double interp_error;  ///< |interpolated - exact| <= 0.866 s (corners within 0.866 s, 1-Lipschitz)
  /// A band voxel at the band's edge has every corner at least this far from
  /// the surface ((dilation - 1) s): see the voxel cull in oracle_evaluate.cpp.
  double band_edge_mm;
  double reach;  ///< the broad phase's reach (the exact level searches this far)

  // The current cell.
  SdfSampler::GridPoint cell;  ///< grid point of the cell's sample centre in L
  Eigen::Vector3f cell_centre_U = Eigen::Vector3f::Zero();  ///< that centre in U
  bool cell_known = false;                                  ///< the field is known at the centre
  double cell_d = 0.0;                                      ///< its interpolated value
  double cell_r = 0.0;  ///< the samples' largest distance from the centre
  UnknownSide unknown_side = UnknownSide::kMaybeInterior;

  QueryContext(const Eigen::Isometry3d& X, const OracleRequest& r, const NarrowBandSdf& sdf,
               double reach_mm)
      : X_LU(X),
        request(r),
        sampler(sdf),
        M(Eigen::Matrix4f::Zero()),
        outer(std::max(r.contact_band_mm, r.residuals ? r.residual_band_mm : 0.0)),
        s(sdf.voxel_size_mm()),
        band_mm(sdf.band_mm()),
        interp_error(kCubeCircumradius * s),
        band_edge_mm(band_mm - s),
        reach(reach_mm) {
    A = X.linear() * sampler.inv_voxel_size();
    b = (X.translation() - sampler.origin()) * sampler.inv_voxel_size();
    M.topLeftCorner<3, 3>() = A.cast<float>();
    outer_float = static_cast<float>(outer);
    if (static_cast<double>(outer_float) < outer) {
      outer_float = std::nextafter(outer_float, std::numeric_limits<float>::infinity());
    }
  }

  /// The side of the unknown samples (outside the band) within r of a point c
  /// where the field is d (`known`) or unknown. The band holds every point
  /// within band_mm of the surface, so an unknown sample s has |D(s)| >
  /// band_mm, and |D(s) - D(c)| <= r, |d - D(c)| <= interp_error: D(s) > 0
  /// needs d > band_mm - r - interp_error, D(s) < 0 needs d < r + interp_error -
  /// band_mm. With c unknown too and r < band_mm, s is on c's side, which
  /// `interior()` (the lower's voxel class at c) tells.
  template <typename InteriorTest>
  UnknownSide SideOfUnknown(bool known, double d, double r, InteriorTest&& interior) const {
    if (known) {
      if (d > r + interp_error - band_mm + kSlackMm) return UnknownSide::kExterior;
      if (d < band_mm - r - interp_error - kSlackMm) return UnknownSide::kInterior;
      return UnknownSide::kMaybeInterior;
    }
    if (r < band_mm - kSlackMm) return interior() ? UnknownSide::kInterior : UnknownSide::kExterior;
    return UnknownSide::kMaybeInterior;
  }

  /// True when a group of samples within r of a point where the field is d
  /// holds none that counts: the interpolant is the trilinear interpolant of
  /// exact (1-Lipschitz) grid values, so each partial derivative is at most 1
  /// in size and interp(p) >= d - sqrt(3) |p - c|; and interp(p) >= d - |p -
  /// c| - 2 * interp_error through the exact distance. Above `outer` nothing
  /// counts, and d > r + interp_error - band rules out deep samples.
  bool Irrelevant(double d, double r) const {
    return d > outer + std::min(kSqrt3 * r, r + 2.0 * interp_error) + kSlackMm &&
           d > r + interp_error - band_mm + kSlackMm;
  }
};

}  // namespace occlude::collision
