// The clinical judge on hand-made relationships: each target checked (met, missed by how much,
// not measured), and the global search's ranking with it: a Class II seat of more contact
// excluded in constraint mode and ranked below the Class I seat in rank mode.
#include "session/clinical_judge.h"

#include <gtest/gtest.h>

#include <vector>

namespace occlude::test {
namespace {

using analysis::OcclusionClass;
using analysis::Relationships;

Relationships Made(double molar_mm, OcclusionClass molar_class, double overjet_mm) {
  Relationships r;
  for (auto* side : {&r.molar[0], &r.molar[1], &r.canine[0], &r.canine[1]}) {
    side->offset.mm = molar_mm;
    side->occlusion_class = molar_class;
  }
  r.overjet.mm = overjet_mm;
  r.overbite.mm = 2.0;
  r.midline_deviation.mm = 0.4;
  return r;
}

const Relationships kClassI = Made(0.2, OcclusionClass::kI, 2.0);
const Relationships kClassII = Made(6.8, OcclusionClass::kII, 8.5);

// Two seats: index 0 the Class II one with more contact (found first), 1 the Class I one.
std::vector<planner::GlobalProposal> Seats() {
  std::vector<planner::GlobalProposal> seats(2);
  seats[0].basin = 0;
  seats[0].proposal.evaluation.contact_area_mm2 = 20.0;
  seats[0].proposal.evaluation.feasible = true;
  seats[1].basin = 1;
  seats[1].proposal.evaluation.contact_area_mm2 = 16.0;
  seats[1].proposal.evaluation.feasible = true;
  return seats;
}

planner::SeatRanking RankingWith(const app::ClinicalTargets& targets) {
  planner::SeatRanking ranking;
  ranking.judge = [targets](const planner::GlobalProposal& seat) {
    return app::JudgeRelationships(targets, seat.basin == 0 ? kClassII : kClassI);
  };
  return ranking;
}

TEST(ClinicalJudgeTest, ChecksEveryTargetOfTheDefaultRanking) {
  const app::ClinicalTargets defaults;
  const std::vector<app::TargetCheck> met = app::CheckTargets(defaults, kClassI);
  ASSERT_EQ(met.size(), 7u);
  for (const app::TargetCheck& c : met) EXPECT_TRUE(c.has_value && c.met) << c.key;
  const planner::SeatJudgement j = app::JudgeRelationships(defaults, kClassII);
  // Four sides of class II (1 each) and the overjet 5.5 mm over 3.
  EXPECT_DOUBLE_EQ(j.penalty, 4.0 + 5.5);
  EXPECT_TRUE(j.admissible) << "rank mode never excludes";
  EXPECT_NE(j.note.find("molar_class_right II"), std::string::npos) << j.note;
}

TEST(ClinicalJudgeTest, AMeasureNotGivenIsNotMeasuredAndCostsNothing) {
  Relationships r = kClassI;
  r.overjet.mm.reset();
  r.overjet.note = "no incisor landmarks";
  app::ClinicalTargets t;
  t.mode = app::ClinicalTargets::Mode::kConstraint;
  const std::vector<app::TargetCheck> checks = app::CheckTargets(t, r);
  const app::TargetCheck& overjet = checks[4];
  EXPECT_EQ(overjet.key, "overjet_mm");
  EXPECT_FALSE(overjet.has_value);
  EXPECT_NE(overjet.measured.find("no incisor landmarks"), std::string::npos);
  const planner::SeatJudgement j = app::JudgeRelationships(t, r);
  EXPECT_TRUE(j.admissible);
  EXPECT_EQ(j.penalty, 0.0);
}

TEST(ClinicalJudgeTest, ConstraintModeExcludesTheClassIISeat) {
  app::ClinicalTargets t;
  t.mode = app::ClinicalTargets::Mode::kConstraint;
  const planner::RankedSeats ranked = planner::RankSeats(Seats(), RankingWith(t), 4);
  ASSERT_EQ(ranked.proposals.size(), 1u);
  EXPECT_EQ(ranked.proposals[0].basin, 1);
  ASSERT_EQ(ranked.excluded.size(), 1u);
  EXPECT_EQ(ranked.excluded[0].basin, 0);
  EXPECT_FALSE(ranked.excluded[0].judgement.admissible);
  EXPECT_NE(ranked.excluded[0].judgement.note.find("molar_class"), std::string::npos);
}

TEST(ClinicalJudgeTest, RankModeRanksTheClassIISeatBelow) {
  const app::ClinicalTargets t;  // the default ranking
  const planner::RankedSeats ranked = planner::RankSeats(Seats(), RankingWith(t), 4);
  ASSERT_EQ(ranked.proposals.size(), 2u);
  EXPECT_TRUE(ranked.excluded.empty());
  EXPECT_EQ(ranked.proposals[0].basin, 1) << "Class I first among seats of comparable contact";
  EXPECT_EQ(ranked.proposals[1].basin, 0);
  // A Class II target turns the order round.
  app::ClinicalTargets class2;
  class2.molar_class = {std::string("II"), std::string("II")};
  class2.canine_class = {std::nullopt, std::nullopt};
  class2.overjet_mm.reset();
  EXPECT_EQ(planner::RankSeats(Seats(), RankingWith(class2), 4).proposals[0].basin, 0);
}

// The targets in one line, as validate --global's summary names them.
TEST(ClinicalJudgeTest, TargetsLineNamesEveryTargetAndTheMode) {
  EXPECT_EQ(app::TargetsLine(app::ClinicalTargets{}),
            "molar I/I, canine I/I, overjet [1.0, 3.0] mm, overbite [1.0, 3.0] mm, midline <= "
            "2.0 mm; rank");
  app::ClinicalTargets molar_only;
  molar_only.canine_class = {std::nullopt, std::nullopt};
  molar_only.molar_class[1] = "II";
  molar_only.overjet_mm = molar_only.overbite_mm = std::nullopt;
  molar_only.midline_max_mm = std::nullopt;
  molar_only.mode = app::ClinicalTargets::Mode::kConstraint;
  EXPECT_EQ(app::TargetsLine(molar_only), "molar I/II, canine -/-; constraint");
}

}  // namespace
}  // namespace occlude::test
