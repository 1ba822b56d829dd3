// Plausibility warnings for a jaw pair (see jaw_checks.h).
#include "session/jaw_checks.h"

#include <sstream>

namespace occlude::app {
namespace {

// Vertices within this of each other count as the same point (mm).
constexpr double kSamePointMm = 1e-9;

Eigen::AlignedBox3d BoxAt(const io::TriangleMesh& mesh, const Eigen::Isometry3d& X) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(X * v);
  return box;
}

// Euclidean gap between two boxes (0 when they overlap).
double Gap(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  const Eigen::Vector3d apart =
      (b.min() - a.max()).cwiseMax(a.min() - b.max()).cwiseMax(Eigen::Vector3d::Zero());
  return apart.norm();
}

bool SameSurface(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U,
                 const Eigen::Isometry3d& X_LU) {
  if (lower_L.num_vertices() != upper_U.num_vertices() || lower_L.triangles != upper_U.triangles)
    return false;
  for (std::size_t i = 0; i < lower_L.num_vertices(); ++i) {
    if ((lower_L.vertices[i] - X_LU * upper_U.vertices[i]).cwiseAbs().maxCoeff() > kSamePointMm)
      return false;
  }
  return true;
}

}  // namespace

std::vector<std::string> JawPairWarnings(const io::TriangleMesh& lower_L,
                                         const io::TriangleMesh& upper_U,
                                         const Eigen::Isometry3d& X_LU,
                                         const std::string& lower_name,
                                         const std::string& upper_name) {
  std::vector<std::string> warnings;
  if (lower_L.empty() || upper_U.empty()) return warnings;
  if (SameSurface(lower_L, upper_U, X_LU)) {
    warnings.push_back(
        upper_name + " and " + lower_name +
        ": the upper and lower jaws are the same surface, so they overlap everywhere and "
        "the contact and penetration figures mean nothing; check the file names");
    return warnings;
  }
  const double gap = Gap(BoxAt(lower_L, Eigen::Isometry3d::Identity()), BoxAt(upper_U, X_LU));
  if (gap > kJawsFarApartMm) {
    std::ostringstream s;
    s.precision(3);
    s << upper_name << " and " << lower_name << ": the jaws are " << gap
      << " mm apart (between their bounding boxes), so the two files may not share a frame; export "
         "both "
         "from the same scan or registration";
    warnings.push_back(s.str());
  }
  return warnings;
}

}  // namespace occlude::app
