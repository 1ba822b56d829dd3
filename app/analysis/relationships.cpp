// The clinical relationships (relationships.h), one function per measure of clinical.md.
#include "relationships.h"

#include <cmath>
#include <map>
#include <tuple>

#include "geometry_util.h"

namespace occlude::analysis {
namespace {

using io::LandmarkType;

constexpr double kClassLimitMm = 1.5;
constexpr double kEndOnLimitMm = 4.0;

// Landmarks of both jaws in L by (jaw, tooth, type).
class Points {
 public:
  void Add(const std::vector<io::Landmark>& landmarks, const Eigen::Isometry3d& X) {
    for (const io::Landmark& l : landmarks) map_[{l.jaw, l.tooth_fdi, l.type}] = X * l.p;
  }
  const Eigen::Vector3d* Get(io::Jaw jaw, int fdi, LandmarkType type) const {
    const auto it = map_.find({jaw, fdi, type});
    return it == map_.end() ? nullptr : &it->second;
  }

 private:
  std::map<std::tuple<io::Jaw, int, LandmarkType>, Eigen::Vector3d> map_;
};

std::string Name(io::Jaw jaw, int fdi, LandmarkType type) {
  return std::string(io::ToString(jaw)) + " " + std::to_string(fdi) + " " + io::ToString(type);
}

bool IsOcclusal(LandmarkType type) {
  return type != LandmarkType::kMesial && type != LandmarkType::kDistal &&
         type != LandmarkType::kFacial && type != LandmarkType::kLingual;
}

Eigen::Vector3d Mean(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& x : p) sum += x;
  return sum / static_cast<double>(p.size());
}

// The mesio-distal direction of a lower tooth in the occlusal plane (unit), or nullopt.
std::optional<Eigen::Vector3d> MesioDistal(const Points& pts, int fdi, const ArchFrame& f) {
  const Eigen::Vector3d* m = pts.Get(io::Jaw::kLower, fdi, LandmarkType::kMesial);
  const Eigen::Vector3d* d = pts.Get(io::Jaw::kLower, fdi, LandmarkType::kDistal);
  if (!m || !d) return std::nullopt;
  Eigen::Vector3d t = *m - *d;
  t -= t.dot(f.occlusal_J) * f.occlusal_J;
  if (t.norm() < 1e-9) return std::nullopt;
  return t.normalized();
}

// Mean over the two sides of dot(upper - lower, axis) for incisal-edge pairs (11, 41), (21, 31).
Measure IncisorMeasure(const Points& pts, const Eigen::Vector3d& axis, double sign) {
  Measure m;
  double sum = 0.0;
  int n = 0;
  for (const auto& [u, l] : {std::pair{11, 41}, std::pair{21, 31}}) {
    const Eigen::Vector3d* pu = pts.Get(io::Jaw::kUpper, u, LandmarkType::kIncisalEdge);
    const Eigen::Vector3d* pl = pts.Get(io::Jaw::kLower, l, LandmarkType::kIncisalEdge);
    if (!pu || !pl) {
      m.note += (m.note.empty() ? "" : "; ") + std::string("no ") +
                (!pu ? Name(io::Jaw::kUpper, u, LandmarkType::kIncisalEdge)
                     : Name(io::Jaw::kLower, l, LandmarkType::kIncisalEdge));
      continue;
    }
    sum += sign * (*pu - *pl).dot(axis);
    ++n;
  }
  if (n > 0) m.mm = sum / n;
  if (n == 1) m.note = "one side only: " + m.note;
  return m;
}

Measure Midline(const Points& pts, const ArchFrame& f) {
  Measure m;
  std::vector<Eigen::Vector3d> p;
  for (const auto& [jaw, fdi] : {std::pair{io::Jaw::kUpper, 11}, std::pair{io::Jaw::kUpper, 21},
                                 std::pair{io::Jaw::kLower, 41}, std::pair{io::Jaw::kLower, 31}}) {
    const Eigen::Vector3d* x = pts.Get(jaw, fdi, LandmarkType::kMesial);
    if (!x) {
      m.note = "no " + Name(jaw, fdi, LandmarkType::kMesial);
      return m;
    }
    p.push_back(*x);
  }
  m.mm = (0.5 * (p[0] + p[1]) - 0.5 * (p[2] + p[3])).dot(f.lateral_J);
  return m;
}

// Offset of an upper point from the midpoint of two lower points along t of a lower tooth.
Measure Offset(const Points& pts, const ArchFrame& f, int upper, LandmarkType upper_type,
               int lower_a, LandmarkType type_a, int lower_b, LandmarkType type_b, int t_tooth) {
  Measure m;
  const Eigen::Vector3d* u = pts.Get(io::Jaw::kUpper, upper, upper_type);
  const Eigen::Vector3d* a = pts.Get(io::Jaw::kLower, lower_a, type_a);
  const Eigen::Vector3d* b = pts.Get(io::Jaw::kLower, lower_b, type_b);
  const std::optional<Eigen::Vector3d> t = MesioDistal(pts, t_tooth, f);
  if (!u)
    m.note = "no " + Name(io::Jaw::kUpper, upper, upper_type);
  else if (!a)
    m.note = "no " + Name(io::Jaw::kLower, lower_a, type_a);
  else if (!b)
    m.note = "no " + Name(io::Jaw::kLower, lower_b, type_b);
  else if (!t)
    m.note = "no mesial and distal landmarks of lower " + std::to_string(t_tooth);
  else
    m.mm = (*u - 0.5 * (*a + *b)).dot(*t);
  return m;
}

void Crossbite(const Points& pts, const ArchFrame& f, Relationships* r) {
  for (const int quadrant : {1, 2}) {
    for (int position = 4; position <= 7; ++position) {
      const int upper = 10 * quadrant + position;
      const int lower = 10 * (quadrant == 1 ? 4 : 3) + position;
      const LandmarkType type = position <= 5 ? LandmarkType::kBuccalCusp : LandmarkType::kMbCusp;
      const Eigen::Vector3d* u = pts.Get(io::Jaw::kUpper, upper, type);
      const Eigen::Vector3d* l = pts.Get(io::Jaw::kLower, lower, type);
      if (!u || !l) {
        if (u || l) r->crossbite_unchecked.push_back(upper);
        continue;
      }
      // Outward normal of the arch at the lower tooth: across its mesio-distal direction,
      // towards its side (the patient's left is +x).
      const double side = quadrant == 2 ? 1.0 : -1.0;
      Eigen::Vector3d n = side * f.lateral_J;
      if (const auto t = MesioDistal(pts, lower, f)) {
        n = f.occlusal_J.cross(*t).normalized();
        if (n.dot(side * f.lateral_J) < 0.0) n = -n;
      }
      if ((*u - *l).dot(n) < 0.0) r->crossbite.push_back(upper);
    }
  }
}

}  // namespace

const char* ToString(OcclusionClass c) {
  return c == OcclusionClass::kI ? "I" : (c == OcclusionClass::kII ? "II" : "III");
}

SideRelationship Classify(Measure offset) {
  SideRelationship s;
  s.offset = std::move(offset);
  if (!s.offset.mm) return s;
  const double v = *s.offset.mm;
  s.occlusion_class = std::abs(v) <= kClassLimitMm
                          ? OcclusionClass::kI
                          : (v > 0.0 ? OcclusionClass::kII : OcclusionClass::kIII);
  s.end_on = std::abs(v) > kClassLimitMm && std::abs(v) <= kEndOnLimitMm;
  return s;
}

std::optional<ArchFrame> LandmarkFrame(const std::vector<io::Landmark>& upper_L,
                                       const std::vector<io::Landmark>& lower_L, std::string* why) {
  std::vector<Eigen::Vector3d> occlusal, upper, lower, right, left, incisors, molars;
  for (const auto* set : {&upper_L, &lower_L}) {
    for (const io::Landmark& l : *set) {
      if (IsOcclusal(l.type)) occlusal.push_back(l.p);
      (l.jaw == io::Jaw::kUpper ? upper : lower).push_back(l.p);
      const int position = io::ToothPosition(l.tooth_fdi);
      if (position == 6 || position == 7) {
        (io::IsLeftSide(l.tooth_fdi) ? left : right).push_back(l.p);
        molars.push_back(l.p);
      }
      if (position == 1) incisors.push_back(l.p);
    }
  }
  if (occlusal.size() < 3 || upper.empty() || lower.empty() || right.empty() || left.empty() ||
      incisors.empty()) {
    *why =
        "the landmarks do not span the frame (occlusal landmarks of both jaws, molar "
        "landmarks on both sides and incisor landmarks are needed)";
    return std::nullopt;
  }
  ArchFrame f;
  const Plane plane = FitPlane(occlusal);
  f.occlusal_J = plane.normal.dot(Mean(upper) - Mean(lower)) >= 0.0 ? plane.normal : -plane.normal;
  Eigen::Vector3d x = Mean(left) - Mean(right);
  x -= x.dot(f.occlusal_J) * f.occlusal_J;
  if (x.norm() < 1e-9) {
    *why = "the right and left molar landmarks coincide across the occlusal plane";
    return std::nullopt;
  }
  f.lateral_J = x.normalized();
  f.anterior_J = f.occlusal_J.cross(f.lateral_J);
  if (f.anterior_J.dot(Mean(incisors) - Mean(molars)) < 0.0) f.anterior_J = -f.anterior_J;
  f.origin_J = plane.point;
  return f;
}

Relationships ComputeRelationships(const std::vector<io::Landmark>& upper_U,
                                   const std::vector<io::Landmark>& lower_L,
                                   const Eigen::Isometry3d& X_LU,
                                   const std::optional<ArchFrame>& lower_frame_L) {
  Relationships r;
  std::vector<io::Landmark> upper_L = upper_U;
  for (io::Landmark& l : upper_L) l.p = X_LU * l.p;
  std::string why;
  std::optional<ArchFrame> frame = LandmarkFrame(upper_L, lower_L, &why);
  r.frame_source = "landmarks";
  if (!frame) {
    frame = lower_frame_L;
    r.frame_source = "lower arch";
  }
  if (!frame) {
    const std::string none = "no frame: " + why + ", and no lower arch frame was given";
    for (Measure* m : {&r.overjet, &r.overbite, &r.midline_deviation}) m->note = none;
    for (SideRelationship* s : {&r.molar[0], &r.molar[1], &r.canine[0], &r.canine[1]}) {
      s->offset.note = none;
    }
    r.frame_source.clear();
    return r;
  }
  r.frame_L = *frame;
  Points pts;
  pts.Add(upper_L, Eigen::Isometry3d::Identity());
  pts.Add(lower_L, Eigen::Isometry3d::Identity());
  const ArchFrame& f = *frame;
  r.overjet = IncisorMeasure(pts, f.anterior_J, 1.0);
  r.overbite = IncisorMeasure(pts, f.occlusal_J, -1.0);
  r.midline_deviation = Midline(pts, f);
  for (const int side : {0, 1}) {
    const int q_up = side == 0 ? 1 : 2, q_low = side == 0 ? 4 : 3;
    r.molar[side] = Classify(Offset(pts, f, 10 * q_up + 6, LandmarkType::kMbCusp, 10 * q_low + 6,
                                    LandmarkType::kMbCusp, 10 * q_low + 6,
                                    LandmarkType::kMiddleBuccalCusp, 10 * q_low + 6));
    r.canine[side] = Classify(Offset(pts, f, 10 * q_up + 3, LandmarkType::kCuspTip, 10 * q_low + 3,
                                     LandmarkType::kDistal, 10 * q_low + 4, LandmarkType::kMesial,
                                     10 * q_low + 3));
  }
  Crossbite(pts, f, &r);
  return r;
}

}  // namespace occlude::analysis
