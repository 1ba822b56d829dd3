// Pose file reading and rigid-transform validation (see pose_file.h).
#include "config/pose_file.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/user_error.h"

namespace occlude::app {

std::string RigidTransformError(const Eigen::Matrix4d& m) {
  if (!m.allFinite()) return "matrix has NaN or infinite entries";
  if (!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12)) return "last row is not 0 0 0 1";
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  const double err = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (err > 1e-6) {
    std::ostringstream s;
    s << "rotation part is not orthonormal (|R^T R - I| = " << err
      << "); the pose must be rigid: no scale or shear";
    return s.str();
  }
  if (R.determinant() < 0) return "rotation part is a reflection (determinant -1)";
  return "";
}

Eigen::Isometry3d ReadPoseFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw UserError(file.string() + ": cannot open the pose file");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    // JSON has no NaN or infinity; say so, since that is how they end up in a pose file.
    throw UserError(file.string() + ": not valid JSON (" + e.what() +
                    "); the matrix must hold finite numbers (JSON has no NaN or infinity)");
  }
  const char* key = j.contains("X_LU") ? "X_LU" : (j.contains("matrix") ? "matrix" : nullptr);
  if (!j.is_object() || key == nullptr) {
    throw UserError(file.string() + ": no \"X_LU\" or \"matrix\" entry (expected a 4x4 array)");
  }
  const nlohmann::json& rows = j[key];
  Eigen::Matrix4d m;
  if (!rows.is_array() || rows.size() != 4)
    throw UserError(file.string() + ": \"" + key + "\" is not a 4x4 array");
  for (int r = 0; r < 4; ++r) {
    const auto& row = rows[static_cast<std::size_t>(r)];
    if (!row.is_array() || row.size() != 4)
      throw UserError(file.string() + ": \"" + key + "\" is not a 4x4 array");
    for (int c = 0; c < 4; ++c) {
      const auto& v = row[static_cast<std::size_t>(c)];
      if (!v.is_number()) {
        throw UserError(file.string() + ": \"" + key +
                        "\" has a non-number entry (NaN must not be used)");
      }
      m(r, c) = v.get<double>();
    }
  }
  const std::string err = RigidTransformError(m);
  if (!err.empty()) throw UserError(file.string() + ": " + err);
  Eigen::Isometry3d X;
  X.matrix() = m;
  return X;
}

}  // namespace occlude::app
