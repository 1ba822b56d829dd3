// The dental arches as the global search sees them (JawArch, in each jaw's own
// frame J), their coarse alignment (the upper brought onto the lower in a
// typical relationship: occlusal planes facing, midlines and anterior
// directions matched, the upper's incisal point a typical overjet ahead of and
// overbite over the lower's, then the arch curves fitted in the occlusal plane
// with the upper curve outside the lower by the overjet), and the shift of one
// pose from another in the lower's arch frame. Millimetres; degrees at the
// interface.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "occlude/collision/oracle.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::planner {

/// One dental arch in its jaw's own frame J (L for the lower jaw, U for the upper).
///
/// Handedness: lateral_J points to the patient's left and occlusal_J out of the jaw's crowns,
/// so for the lower jaw (occlusal up) lateral = occlusal x anterior, i.e. occlusal = anterior x
/// lateral (collision::ArchFrame's convention and the synthetic pair's frames), and for the
/// upper jaw (occlusal down) occlusal = lateral x anterior. The search checks only that the two
/// arches agree: the upper's (lateral, anterior, -occlusal) must have the handedness of the
/// lower's (lateral, anterior, occlusal); see ValidateJawArches.
struct JawArch {
  Eigen::Vector3d origin_J = Eigen::Vector3d::Zero();  ///< incisal point: the dental midline at
                                                       ///< the central incisors' incisal edges,
                                                       ///< projected onto the occlusal plane (mm)
  Eigen::Vector3d occlusal_J = Eigen::Vector3d::UnitY();  ///< unit normal of the occlusal plane,
                                                          ///< out of this jaw's crowns (towards
                                                          ///< the opposing jaw when they occlude)
  Eigen::Vector3d anterior_J = Eigen::Vector3d::UnitZ();  ///< unit, in the occlusal plane,
                                                          ///< towards the incisors
  Eigen::Vector3d lateral_J = Eigen::Vector3d::UnitX();   ///< unit, the patient's left
  std::vector<Eigen::Vector3d> curve_J;  ///< arch curve (cusp tips / incisal edges), right to left
};

/// Throws std::invalid_argument naming the arch ("lower" / "upper") and field when an arch is
/// unusable: a non-finite value, axes not unit or not orthogonal (within 0.05), fewer than 4
/// curve points, or when the two arches cannot face each other (opposite handedness: one jaw
/// mirrored, or an upper given as a lower).
void ValidateJawArches(const JawArch& lower_L, const JawArch& upper_U);

/// The typical relationship the alignment aims at (clinical.md: both normal at 1-3 mm).
struct AlignmentSettings {
  double overjet_mm = 2.0;   ///< upper incisal point ahead of the lower's along anterior
  double overbite_mm = 2.0;  ///< upper incisal point below the lower's along occlusal
  bool fit_curves = true;    ///< refine lateral, anterior and yaw by the 2-D curve fit
  /// The curve fit is trusted up to these moves from the frame alignment; beyond them the
  /// frame alignment is kept and the result warns (a fit that slid along the arch). 15 deg:
  /// the arch frames of c2-ios are 9 deg apart in yaw and its fit's correction is 10.2 deg.
  double max_fit_shift_mm = 6.0;
  double max_fit_yaw_deg = 15.0;
};

struct ArchAlignment {
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();         ///< the aligned pose
  Eigen::Isometry3d X_LU_frames = Eigen::Isometry3d::Identity();  ///< before the curve fit
  /// What the curve fit moved (in the lower's arch frame, mm; yaw in degrees about the lower's
  /// occlusal axis through the incisal target, as ArchShift), and the RMS distance of the upper
  /// curve from the lower curve offset outward by the overjet, before and after.
  double fit_lateral_mm = 0.0, fit_anterior_mm = 0.0, fit_yaw_deg = 0.0;
  double fit_rms_before_mm = 0.0, fit_rms_mm = 0.0;
  std::vector<std::string> warnings;
};

/// Aligns the upper arch onto the lower (see the file comment). Throws std::invalid_argument
/// from ValidateJawArches or for negative / non-finite settings (naming the field).
ArchAlignment AlignArches(const JawArch& lower_L, const JawArch& upper_U,
                          const AlignmentSettings& settings = {});

/// The rigid motion from X_LU_from to X_LU_to, X_LU_to = T(p_LPivot + t) R T(-p_LPivot)
/// X_LU_from, in the lower's arch frame: t along lateral, anterior and occlusal (mm); R's
/// rotation vector about occlusal (yaw), lateral (pitch) and anterior (roll), in degrees.
struct ArchShift {
  double lateral_mm = 0.0;   ///< + = to the patient's left
  double sagittal_mm = 0.0;  ///< + = the upper forward (towards the incisors)
  double vertical_mm = 0.0;  ///< + = the upper away from the lower (opening)
  double yaw_deg = 0.0, pitch_deg = 0.0, roll_deg = 0.0;
};
ArchShift ShiftBetween(const Eigen::Isometry3d& X_LU_from, const Eigen::Isometry3d& X_LU_to,
                       const Eigen::Vector3d& p_LPivot, const JawArch& lower_L);
/// The inverse of ShiftBetween: X_LU_to from X_LU_from and a shift.
Eigen::Isometry3d ApplyShift(const Eigen::Isometry3d& X_LU_from, const ArchShift& shift,
                             const Eigen::Vector3d& p_LPivot, const JawArch& lower_L);

/// The lower's arch as a collision::ArchFrame in L (origin at the incisal point; the anterior
/// region the front 35 % of the curve's depth), for the planner's settle axis and shares.
collision::ArchFrame FrameOf(const JawArch& lower_L);

/// The occlusal point of one tooth (FDI number, point in the jaw's frame J), for the arch from
/// tooth points below.
struct ToothPoint {
  int fdi = 0;
  Eigen::Vector3d p_J = Eigen::Vector3d::Zero();
};

/// A jaw's arch from tooth points alone, without the app's arch analysis (which is what the
/// global search of a session steps by): for tools and tests that hold only tooth parts or
/// landmark points (bench/global_measure, the planner's tests). The curve the points right to left
/// (by FDI number); the occlusal normal the normal of the plane fitted through them, on the side of
/// `occlusal_hint_J` (out of the crowns); lateral the direction from the most distal tooth of the
/// right side to the most distal of the left, in that plane; anterior in the plane, perpendicular
/// to lateral, towards the central incisors; the incisal point the mean of the central incisors'
/// points (else the most anterior point) projected onto the plane. Throws std::invalid_argument for
/// fewer than 4 teeth, teeth of both jaws, or no tooth on one side.
JawArch JawArchFromTeeth(const std::vector<ToothPoint>& teeth,
                         const Eigen::Vector3d& occlusal_hint_J);
/// Per tooth part of a mesh (parts with a Universal tooth number): the centroid of its vertices
/// within `top_mm` of its extreme along occlusal_J (its cusp tips or incisal edge).
std::vector<ToothPoint> ToothTops(const io::TriangleMesh& jaw_J, const Eigen::Vector3d& occlusal_J,
                                  double top_mm = 1.0);

}  // namespace occlude::planner
