// Eigen values as JSON (nlohmann) for the files the commands write: a vector as [x, y, z],
// a 4x4 matrix as four rows.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace occlude::app {

inline nlohmann::json Vec(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

inline nlohmann::json Matrix(const Eigen::Matrix4d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r)
    rows.push_back(nlohmann::json::array({m(r, 0), m(r, 1), m(r, 2), m(r, 3)}));
  return rows;
}

}  // namespace occlude::app
