// The clinical occlusal relationships of two jaws at a pose, exactly as
// ../shared/docs/clinical.md defines them: overjet, overbite, midline deviation, molar and canine
// relationship per side (mm and class), posterior crossbite teeth. A measure whose landmarks are
// missing is left empty and says why.
//
// Frame (clinical.md): from the landmarks when they allow it: z the normal of the plane fitted
// through the occlusal landmarks of both jaws (every type but the contact and surface points:
// cusps, incisal edges, central fossae), lower -> upper; x from the right to the left molars
// (mean of every landmark on teeth 6 and 7 of each side, both jaws) in that plane; y in it
// towards the incisors. Else the lower jaw's detected arch frame. Millimetres, in L.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "arch_analysis.h"
#include "occlude/io/dental.h"

namespace occlude::analysis {

/// One measure: the value, or nothing with the reason; `note` also says what a value rests on
/// when it is partial (one side of two).
struct Measure {
  std::optional<double> mm;
  std::string note;
};

/// Angle's classes of a molar or canine relationship (clinical.md).
enum class OcclusionClass { kI, kII, kIII };
/// "I", "II" or "III".
const char* ToString(OcclusionClass c);

struct SideRelationship {
  Measure offset;  ///< mm, + = upper mesial of its lower reference
  std::optional<OcclusionClass> occlusion_class;
  bool end_on = false;  ///< 1.5 mm < |offset| <= 4 mm ("end-on" in words)
};

struct Relationships {
  ArchFrame frame_L;           ///< the frame the measures are taken in (origin_J = origin_L)
  std::string frame_source;    ///< "landmarks" or "lower arch"
  Measure overjet;             ///< mm along y, upper - lower incisal edges
  Measure overbite;            ///< mm along z, lower - upper incisal edges
  Measure midline_deviation;   ///< mm along x, + = upper midline to the patient's left
  SideRelationship molar[2];   ///< [0] right (16 / 46), [1] left (26 / 36)
  SideRelationship canine[2];  ///< [0] right (13 / 43-44), [1] left (23 / 33-34)
  std::vector<int> crossbite;  ///< upper premolars / molars in posterior crossbite (FDI)
  std::vector<int> crossbite_unchecked;  ///< upper premolars / molars lacking a landmark
};

/// clinical.md's class of an offset: I within +-1.5 mm, II above, III below; end-on 1.5-4 mm.
SideRelationship Classify(Measure offset);

/// The landmark frame of clinical.md from landmarks of both jaws in L; nullopt with `why` when
/// they do not span it (fewer than 3 occlusal landmarks, no molar landmark on a side, no
/// incisor landmark).
std::optional<ArchFrame> LandmarkFrame(const std::vector<io::Landmark>& upper_L,
                                       const std::vector<io::Landmark>& lower_L, std::string* why);

/// The relationships at pose X_LU of the upper landmarks `upper_U` (frame U) over the lower
/// landmarks `lower_L`, in the landmark frame or, when the landmarks do not span it,
/// `lower_frame_L` (the detected lower arch frame; without it nothing is measured).
Relationships ComputeRelationships(const std::vector<io::Landmark>& upper_U,
                                   const std::vector<io::Landmark>& lower_L,
                                   const Eigen::Isometry3d& X_LU,
                                   const std::optional<ArchFrame>& lower_frame_L);

}  // namespace occlude::analysis
