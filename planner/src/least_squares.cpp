// The least-squares model: per-sample signed distances of fixed upper samples
// with analytic Jacobians (the oracle's distance gradient chained through the
// pivot parameterization), used by the Ceres solver and checked in the tests.
#include "occlude/planner/least_squares.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "least_squares_internal.h"
#include "occlude/angles.h"

namespace occlude::planner {
namespace detail {
namespace {
constexpr double kRadPerDeg = RadiansFromDegrees(1.0);
}  // namespace

Eigen::Matrix3d Hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

Eigen::Matrix3d Exp(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  return angle > 0 ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix()
                   : Eigen::Matrix3d::Identity();
}

Eigen::Matrix3d LeftJacobian(const Eigen::Vector3d& w) {
  const double t = w.norm();
  const Eigen::Matrix3d W = Hat(w);
  if (t < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 6.0;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(t)) / (t * t) * W +
         (t - std::sin(t)) / (t * t * t) * W * W;
}

Eigen::Matrix3d LeftJacobianInverse(const Eigen::Vector3d& w) {
  const double t = w.norm();
  const Eigen::Matrix3d W = Hat(w);
  if (t < 1e-6) return Eigen::Matrix3d::Identity() - 0.5 * W + W * W / 12.0;
  const double c = 1.0 / (t * t) - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  return Eigen::Matrix3d::Identity() - 0.5 * W + c * W * W;
}

Vector6d AmbientFromX(const Vector6d& x) {
  Vector6d z = x;
  z.tail<3>() *= kRadPerDeg;
  return z;
}

Vector6d XFromAmbient(const Vector6d& z) {
  Vector6d x = z;
  x.tail<3>() /= kRadPerDeg;
  return x;
}

ResidualMemo::ResidualMemo(const SurfaceResiduals::Impl& model)
    : model_(model), pose_(Vector6d::Zero()), samples_(model.area.size()) {}

namespace {
// The same 6 doubles bit for bit (a point Ceres asks for again is the same point, and -0.0 or a
// NaN is not taken for another value).
bool SameBits6(const double* a, const double* b) {
  for (int k = 0; k < 6; ++k) {
    std::uint64_t x = 0, y = 0;
    std::memcpy(&x, a + k, sizeof x);
    std::memcpy(&y, b + k, sizeof y);
    if (x != y) return false;
  }
  return true;
}
}  // namespace

const ResidualMemo::Sample& ResidualMemo::At(std::size_t i, const double* z, bool jacobians) {
  if (point_ == 0 || !SameBits6(z, pose_.z.data())) {
    pose_ = SurfaceResiduals::Impl::PoseAt(Eigen::Map<const Vector6d>(z));
    ++point_;
  }
  Sample& s = samples_.at(i);
  if (s.point != point_ || (jacobians && !s.has_jacobians)) {
    // Ceres evaluates every block at a point: every sample at once, on the job's threads.
    ForBlocks(samples_.size(), kSamplesPerBlock, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        Sample& sk = samples_[k];
        if (sk.point == point_ && (!jacobians || sk.has_jacobians)) continue;
        model_.Residuals(k, pose_, &sk.hinge, &sk.attraction, jacobians ? &sk.j_hinge : nullptr,
                         jacobians ? &sk.j_attraction : nullptr);
        sk.point = point_;
        sk.has_jacobians = jacobians;
      }
    });
  }
  return s;
}
}  // namespace detail

double SeatSampleCost(double d, double area_mm2, bool attract, const ResidualSettings& settings) {
  double rho = 0.0;
  if (attract && d > 0.0) {
    // Cauchy: b^2 log(1 + s / b^2), s = a m^2, b^2 = c^2 a.
    const double m = std::min(d, settings.window_mm),
                 c2 = settings.attraction_scale_mm * settings.attraction_scale_mm;
    rho += c2 * area_mm2 * std::log1p(m * m / c2);
  }
  const double e = -(d + settings.penetration_allowance_mm);
  if (e > 0.0) {
    // Huber: s if s <= b^2 else 2 b sqrt(s) - b^2, s = w^2 a e^2, b = w sqrt(a) h.
    const double w2a = settings.penetration_weight * settings.penetration_weight * area_mm2;
    const double h = settings.penetration_huber_mm;
    rho += e <= h ? w2a * e * e : w2a * (2.0 * h * e - h * h);
  }
  return 0.5 * rho;
}

SurfaceResiduals::Impl::Impl(const OracleStage& stage_in, const detail::SampleSet& all,
                             const Eigen::Isometry3d& X_LU_base, const Eigen::Isometry3d& X_LU_ref,
                             const Eigen::Vector3d& p_LPivot, const ResidualSettings& settings_in,
                             std::size_t max_samples, const std::vector<bool>* excluded)
    : stage(stage_in), X_ref(X_LU_ref), pivot(p_LPivot), settings(settings_in) {
  std::vector<char> within(all.size(), 0);
  detail::ForBlocks(all.size(), detail::kSamplesPerBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (excluded && (*excluded)[i]) continue;
      double d = 0.0;
      bool deep = false;
      within[i] = detail::StageDistance(stage, X_LU_base * all.p_U[i], settings.range_mm, &d,
                                        nullptr, &deep) &&
                  d <= settings.range_mm;
    }
  });
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (within[i]) near.push_back(i);
  }
  const std::size_t stride =
      max_samples > 0 ? std::max<std::size_t>(1, (near.size() + max_samples - 1) / max_samples) : 1;
  for (std::size_t k = 0; k < near.size(); k += stride) {
    const std::size_t i = near[k];
    v_L.push_back(X_ref * all.p_U[i] - pivot);
    area.push_back(all.area_mm2[i] * static_cast<double>(stride));
    attract.push_back(all.facing[i] >= settings.attraction_min_facing);
  }
}

SurfaceResiduals::Impl::PoseAt::PoseAt(const Vector6d& z_in)
    : z(z_in), R(detail::Exp(z.tail<3>())), Jl(detail::LeftJacobian(z.tail<3>())) {}

double SurfaceResiduals::Impl::Distance(std::size_t i, const PoseAt& pose, Row6d* gradient) const {
  const Eigen::Vector3d Rv = pose.R * v_L[i];
  const Eigen::Vector3d q = pivot + pose.z.head<3>() + Rv;
  double d = 0.0;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  bool deep = false;
  if (!detail::StageDistance(stage, q, std::max(settings.range_mm, 0.5), &d, &n, &deep)) {
    // Outside the field: a constant (zero gradient), deep inside or far away.
    d = deep ? -stage.oracle->lower_sdf().band_mm() : settings.range_mm + 1.0;
    n.setZero();
  }
  if (gradient) {
    gradient->head<3>() = n.transpose();
    gradient->tail<3>() = Rv.cross(n).transpose() * pose.Jl;
  }
  return d;
}

void SurfaceResiduals::Impl::Residuals(std::size_t i, const PoseAt& pose, double* hinge,
                                       double* attraction, Row6d* j_hinge,
                                       Row6d* j_attraction) const {
  Row6d g;
  const double d = Distance(i, pose, (j_hinge || j_attraction) ? &g : nullptr);
  const double s = std::sqrt(area[i]);
  const double wp = settings.penetration_weight * s;
  const double e = d + settings.penetration_allowance_mm;  // < 0: beyond the allowance
  const bool attracted = attract[i] && d > 0.0 && d < settings.window_mm;
  *hinge = e < 0.0 ? wp * e : 0.0;
  *attraction = (!attract[i] || d <= 0.0) ? 0.0 : s * std::min(d, settings.window_mm);
  if (j_hinge) *j_hinge = e < 0.0 ? Row6d(wp * g) : Row6d::Zero();
  if (j_attraction) *j_attraction = attracted ? Row6d(s * g) : Row6d::Zero();
}

SurfaceResiduals::SurfaceResiduals(const OracleStage& stage, const Eigen::Isometry3d& X_LU_base,
                                   const Eigen::Isometry3d& X_LU_ref,
                                   const Eigen::Vector3d& p_LPivot,
                                   const ResidualSettings& settings, std::size_t max_samples) {
  const detail::SampleSet all =
      detail::OcclusalSamples(stage.oracle->upper_tree().mesh(), X_LU_base,
                              stage.oracle->arch().occlusal_L, detail::StageSpacing(stage));
  impl_ = std::make_unique<Impl>(stage, all, X_LU_base, X_LU_ref, p_LPivot, settings, max_samples);
}

SurfaceResiduals::~SurfaceResiduals() = default;
SurfaceResiduals::SurfaceResiduals(SurfaceResiduals&&) noexcept = default;
SurfaceResiduals& SurfaceResiduals::operator=(SurfaceResiduals&&) noexcept = default;

int SurfaceResiduals::size() const { return static_cast<int>(2 * impl_->area.size()); }

void SurfaceResiduals::Evaluate(const PoseParameters& params, Eigen::VectorXd* residuals,
                                Eigen::MatrixXd* jacobian) const {
  const Impl::PoseAt pose(detail::AmbientFromX(detail::FromParameters(params)));
  const auto n = static_cast<Eigen::Index>(impl_->area.size());
  residuals->resize(2 * n);
  if (jacobian) jacobian->resize(2 * n, 6);
  // Per degree instead of per radian for the rotation columns.
  Row6d unit = Row6d::Ones();
  unit.tail<3>() *= RadiansFromDegrees(1.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    Row6d jh, ja;
    impl_->Residuals(static_cast<std::size_t>(i), pose, &(*residuals)[2 * i],
                     &(*residuals)[2 * i + 1], jacobian ? &jh : nullptr, jacobian ? &ja : nullptr);
    if (jacobian) {
      jacobian->row(2 * i) = jh.cwiseProduct(unit);
      jacobian->row(2 * i + 1) = ja.cwiseProduct(unit);
    }
  }
}

}  // namespace occlude::planner
