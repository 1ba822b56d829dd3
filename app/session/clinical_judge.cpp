// The clinical targets checked at a pose and the global search's judge (see clinical_judge.h).
#include "session/clinical_judge.h"

#include <cmath>
#include <sstream>

#include "base/text_format.h"

namespace occlude::app {
namespace {

std::string MmText(double v) { return Fixed(v, 1) + " mm"; }

TargetCheck ClassCheck(const std::string& key, const std::string& wanted,
                       const analysis::SideRelationship& side) {
  TargetCheck c{key, wanted, "", false, false, 0.0};
  if (!side.offset.mm || !side.occlusion_class) {
    c.measured = "not measured: " + side.offset.note;
    return c;
  }
  const std::string got = analysis::ToString(*side.occlusion_class);
  c.has_value = true;
  c.measured = got + " (" + (*side.offset.mm >= 0 ? "+" : "") + MmText(*side.offset.mm) + ")";
  c.met = got == wanted;
  c.miss = c.met ? 0.0 : 1.0;
  return c;
}

TargetCheck IntervalCheck(const std::string& key, const MmInterval& wanted,
                          const analysis::Measure& m) {
  TargetCheck c{key,   "[" + Fixed(wanted.min, 1) + ", " + Fixed(wanted.max, 1) + "] mm",
                "",    false,
                false, 0.0};
  if (!m.mm) {
    c.measured = "not measured: " + m.note;
    return c;
  }
  c.has_value = true;
  c.measured = MmText(*m.mm);
  c.miss = std::max({0.0, wanted.min - *m.mm, *m.mm - wanted.max});
  c.met = c.miss == 0.0;
  return c;
}

TargetCheck MidlineCheck(double max_mm, const analysis::Measure& m) {
  TargetCheck c{"midline_max_mm", "<= " + MmText(max_mm), "", false, false, 0.0};
  if (!m.mm) {
    c.measured = "not measured: " + m.note;
    return c;
  }
  c.has_value = true;
  c.measured = MmText(*m.mm);
  c.miss = std::max(0.0, std::abs(*m.mm) - max_mm);
  c.met = c.miss == 0.0;
  return c;
}

std::string ClassText(const analysis::SideRelationship& s) {
  return s.occlusion_class ? analysis::ToString(*s.occlusion_class) : "?";
}

std::string MeasureText(const analysis::Measure& m) { return m.mm ? MmText(*m.mm) : "?"; }

}  // namespace

std::vector<TargetCheck> CheckTargets(const ClinicalTargets& targets,
                                      const analysis::Relationships& r) {
  std::vector<TargetCheck> checks;
  const char* const side_names[2] = {"_right", "_left"};
  for (int side = 0; side < 2; ++side) {
    if (const auto& w = targets.molar_class[static_cast<std::size_t>(side)])
      checks.push_back(
          ClassCheck(std::string("molar_class") + side_names[side], *w, r.molar[side]));
  }
  for (int side = 0; side < 2; ++side) {
    if (const auto& w = targets.canine_class[static_cast<std::size_t>(side)])
      checks.push_back(
          ClassCheck(std::string("canine_class") + side_names[side], *w, r.canine[side]));
  }
  if (targets.overjet_mm)
    checks.push_back(IntervalCheck("overjet_mm", *targets.overjet_mm, r.overjet));
  if (targets.overbite_mm)
    checks.push_back(IntervalCheck("overbite_mm", *targets.overbite_mm, r.overbite));
  if (targets.midline_max_mm)
    checks.push_back(MidlineCheck(*targets.midline_max_mm, r.midline_deviation));
  return checks;
}

std::string RelationshipsLine(const analysis::Relationships& r) {
  return "molar " + ClassText(r.molar[0]) + "/" + ClassText(r.molar[1]) + ", canine " +
         ClassText(r.canine[0]) + "/" + ClassText(r.canine[1]) + ", overjet " +
         MeasureText(r.overjet) + ", overbite " + MeasureText(r.overbite) + ", midline " +
         MeasureText(r.midline_deviation);
}

std::string TargetsLine(const ClinicalTargets& targets) {
  const auto sides = [](const std::array<std::optional<std::string>, 2>& c) {
    return c[0].value_or("-") + "/" + c[1].value_or("-");
  };
  const auto interval = [](const MmInterval& i) {
    return "[" + Fixed(i.min, 1) + ", " + Fixed(i.max, 1) + "] mm";
  };
  std::string line =
      "molar " + sides(targets.molar_class) + ", canine " + sides(targets.canine_class);
  if (targets.overjet_mm) line += ", overjet " + interval(*targets.overjet_mm);
  if (targets.overbite_mm) line += ", overbite " + interval(*targets.overbite_mm);
  if (targets.midline_max_mm) line += ", midline <= " + MmText(*targets.midline_max_mm);
  return line + "; " + ToString(targets.mode);
}

planner::SeatJudgement JudgeRelationships(const ClinicalTargets& targets,
                                          const analysis::Relationships& r) {
  planner::SeatJudgement j;
  std::string misses;
  for (const TargetCheck& c : CheckTargets(targets, r)) {
    if (!c.has_value || c.met) continue;
    j.penalty += c.miss;
    misses +=
        (misses.empty() ? "" : ", ") + c.key + " " + c.measured + " (wanted " + c.wanted + ")";
  }
  if (targets.mode == ClinicalTargets::Mode::kConstraint && !misses.empty()) j.admissible = false;
  j.note = RelationshipsLine(r) +
           (misses.empty() ? "; every measured target met" : "; misses " + misses);
  return j;
}

planner::SeatJudge ClinicalJudge(const ClinicalTargets& targets, const CaseAnalysis& analysis) {
  return [targets, &analysis](const planner::GlobalProposal& seat) {
    return JudgeRelationships(targets, RelationshipsAt(analysis, seat.proposal.X_LU));
  };
}

}  // namespace occlude::app
