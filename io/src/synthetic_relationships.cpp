// The designed clinical relationships of the synthetic bite: clinical.md's definitions applied
// to the generator's own landmarks at X_LU, in the frame of L (occlusal +y, anterior +z, lateral
// +x: the arch frame of the design).
#include <stdexcept>
#include <string>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

const Eigen::Vector3d kOcclusal = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kAnterior = Eigen::Vector3d::UnitZ();
const Eigen::Vector3d kLateral = Eigen::Vector3d::UnitX();

/// The landmarks of both jaws, all in L.
class Landmarks {
 public:
  Landmarks(const std::vector<Landmark>& lower_L, const std::vector<Landmark>& upper_L)
      : lower_(lower_L), upper_(upper_L) {}

  Eigen::Vector3d operator()(int fdi, LandmarkType type) const {
    for (const std::vector<Landmark>* jaw : {&lower_, &upper_}) {
      for (const Landmark& l : *jaw) {
        if (l.tooth_fdi == fdi && l.type == type) return l.p;
      }
    }
    throw std::logic_error("synthetic landmarks: no " + std::string(ToString(type)) + " on tooth " +
                           std::to_string(fdi));
  }

  /// Unit mesio-distal direction of a lower tooth (mesial - distal) in the occlusal plane.
  Eigen::Vector3d MesialDirection(int fdi) const {
    Eigen::Vector3d t = (*this)(fdi, LandmarkType::kMesial) - (*this)(fdi, LandmarkType::kDistal);
    t -= t.dot(kOcclusal) * kOcclusal;
    return t.normalized();
  }

 private:
  const std::vector<Landmark>& lower_;
  const std::vector<Landmark>& upper_;
};

/// Molar relationship of one side (upper first molar fdi_upper over lower fdi_lower).
double MolarOffset(const Landmarks& at, int fdi_upper, int fdi_lower) {
  const Eigen::Vector3d groove =
      0.5 * (at(fdi_lower, LandmarkType::kMbCusp) + at(fdi_lower, LandmarkType::kMiddleBuccalCusp));
  return (at(fdi_upper, LandmarkType::kMbCusp) - groove).dot(at.MesialDirection(fdi_lower));
}

/// Canine relationship of one side (upper canine over the lower canine / first premolar).
double CanineOffset(const Landmarks& at, int fdi_upper, int fdi_lower_canine) {
  const Eigen::Vector3d embrasure = 0.5 * (at(fdi_lower_canine, LandmarkType::kDistal) +
                                           at(fdi_lower_canine + 1, LandmarkType::kMesial));
  return (at(fdi_upper, LandmarkType::kCuspTip) - embrasure)
      .dot(at.MesialDirection(fdi_lower_canine));
}

}  // namespace

SyntheticRelationships DesignedRelationships(const std::vector<Landmark>& lower_L,
                                             const std::vector<Landmark>& upper_L) {
  const Landmarks at(lower_L, upper_L);
  const LandmarkType edge = LandmarkType::kIncisalEdge, mesial = LandmarkType::kMesial;
  SyntheticRelationships r;
  for (const auto& [upper, lower] : {std::pair{11, 41}, std::pair{21, 31}}) {
    const Eigen::Vector3d d = at(upper, edge) - at(lower, edge);
    r.overjet_mm += 0.5 * d.dot(kAnterior);
    r.overbite_mm -= 0.5 * d.dot(kOcclusal);
  }
  r.midline_deviation_mm =
      (0.5 * (at(11, mesial) + at(21, mesial)) - 0.5 * (at(41, mesial) + at(31, mesial)))
          .dot(kLateral);
  r.molar_mm = {MolarOffset(at, 16, 46), MolarOffset(at, 26, 36)};
  r.canine_mm = {CanineOffset(at, 13, 43), CanineOffset(at, 23, 33)};
  return r;
}

}  // namespace occlude::io::synthetic
