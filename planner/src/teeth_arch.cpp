// A stand-in arch analysis for the global search's tests and measurements: a
// JawArch from one occlusal point per tooth (tooth parts of a mesh, or hand-
// placed landmarks), ordered and oriented by the FDI numbers. The app's arch
// analysis replaces it.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

#include "occlude/io/dental.h"
#include "occlude/planner/arch_alignment.h"

namespace occlude::planner {
namespace {

constexpr std::size_t kMinTeeth = 4;

// Right to left along the arch: the right quadrant from its most distal tooth to the central
// incisor, then the left quadrant from the central incisor out.
int ArchOrder(int fdi) {
  const int position = io::ToothPosition(fdi);
  return io::IsLeftSide(fdi) ? 10 + position : 10 - position;
}

// The normal of the plane through the points (smallest covariance axis), on the side of hint.
Eigen::Vector3d PlaneNormal(const std::vector<Eigen::Vector3d>& points,
                            const Eigen::Vector3d& centroid, const Eigen::Vector3d& hint) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d n = eig.eigenvectors().col(0);
  return n.dot(hint) >= 0.0 ? n : Eigen::Vector3d(-n);
}

void CheckTeeth(const std::vector<ToothPoint>& teeth) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("JawArchFromTeeth: " + what);
  };
  if (teeth.size() < kMinTeeth) {
    fail("needs at least " + std::to_string(kMinTeeth) + " teeth (got " +
         std::to_string(teeth.size()) + ")");
  }
  bool left = false, right = false;
  for (const ToothPoint& t : teeth) {
    if (!io::IsValidFdi(t.fdi)) fail("tooth " + std::to_string(t.fdi) + " is no FDI number");
    if (io::JawOfFdi(t.fdi) != io::JawOfFdi(teeth.front().fdi)) fail("teeth of both jaws");
    if (!t.p_J.allFinite()) fail("tooth " + std::to_string(t.fdi) + ": non-finite point");
    (io::IsLeftSide(t.fdi) ? left : right) = true;
  }
  if (!left || !right) fail("needs teeth on both sides of the midline");
}

}  // namespace

JawArch JawArchFromTeeth(const std::vector<ToothPoint>& teeth,
                         const Eigen::Vector3d& occlusal_hint_J) {
  CheckTeeth(teeth);
  std::vector<ToothPoint> sorted = teeth;
  std::stable_sort(sorted.begin(), sorted.end(), [](const ToothPoint& a, const ToothPoint& b) {
    return ArchOrder(a.fdi) < ArchOrder(b.fdi);
  });
  JawArch arch;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), incisal = Eigen::Vector3d::Zero();
  int incisors = 0;
  for (const ToothPoint& t : sorted) {
    arch.curve_J.push_back(t.p_J);
    centroid += t.p_J;
    if (io::ToothPosition(t.fdi) == 1) {
      incisal += t.p_J;
      ++incisors;
    }
  }
  centroid /= static_cast<double>(sorted.size());
  const Eigen::Vector3d n = PlaneNormal(arch.curve_J, centroid, occlusal_hint_J);
  Eigen::Vector3d across = arch.curve_J.back() - arch.curve_J.front();
  across = (across - across.dot(n) * n).normalized();
  Eigen::Vector3d anterior = across.cross(n);
  const Eigen::Vector3d ends = 0.5 * (arch.curve_J.back() + arch.curve_J.front());
  if (incisors == 0) {
    incisal = *std::max_element(arch.curve_J.begin(), arch.curve_J.end(),
                                [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
                                  return (a - ends).dot(anterior) < (b - ends).dot(anterior);
                                });
  } else {
    incisal /= incisors;
  }
  if ((incisal - ends).dot(anterior) < 0.0) anterior = -anterior;
  arch.occlusal_J = n;
  arch.anterior_J = anterior;
  arch.lateral_J = across;
  arch.origin_J = incisal - (incisal - centroid).dot(n) * n;
  return arch;
}

std::vector<ToothPoint> ToothTops(const io::TriangleMesh& jaw_J, const Eigen::Vector3d& occlusal_J,
                                  double top_mm) {
  const Eigen::Vector3d u = occlusal_J.normalized();
  std::map<int, double> top;  // per part with a tooth number
  for (std::size_t t = 0; t < jaw_J.num_triangles(); ++t) {
    const auto part = static_cast<std::size_t>(jaw_J.triangle_part[t]);
    if (jaw_J.parts[part].tooth_number <= 0) continue;
    auto [it, fresh] =
        top.emplace(static_cast<int>(part), -std::numeric_limits<double>::infinity());
    (void)fresh;
    for (int k = 0; k < 3; ++k) it->second = std::max(it->second, jaw_J.corner(t, k).dot(u));
  }
  std::map<int, std::pair<Eigen::Vector3d, double>> sum;
  for (std::size_t t = 0; t < jaw_J.num_triangles(); ++t) {
    const auto it = top.find(jaw_J.triangle_part[t]);
    if (it == top.end()) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = jaw_J.corner(t, k);
      if (v.dot(u) < it->second - top_mm) continue;
      auto& [p, n] = sum.try_emplace(it->first, Eigen::Vector3d::Zero(), 0.0).first->second;
      p += v;
      n += 1.0;
    }
  }
  std::vector<ToothPoint> out;
  for (const auto& [part, pn] : sum) {
    const int universal = jaw_J.parts[static_cast<std::size_t>(part)].tooth_number;
    out.push_back({io::FdiFromUniversal(universal), pn.first / pn.second});
  }
  return out;
}

}  // namespace occlude::planner
