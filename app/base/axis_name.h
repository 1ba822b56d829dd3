// Axis names of the command line and the config: "x", "+y", "-z" (sign optional).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace occlude::app {

/// The unit vector `text` names ("x", "+x", "-x", likewise y and z), nullopt for anything else
/// (the caller says which key or option was wrong and what it accepts).
inline std::optional<Eigen::Vector3d> AxisFromName(const std::string& text) {
  const bool negative = !text.empty() && text[0] == '-';
  const std::string name = (negative || (!text.empty() && text[0] == '+')) ? text.substr(1) : text;
  if (name != "x" && name != "y" && name != "z") return std::nullopt;
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(name[0] - 'x');
  return negative ? Eigen::Vector3d(-axis) : axis;
}

}  // namespace occlude::app
