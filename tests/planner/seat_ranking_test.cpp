// RankSeats on hand-made seats: without a judge the order is kept; with one,
// the inadmissible seats are set aside, feasible seats of comparable seat depth
// (and contact, when asked) ordered by penalty (ties keep the seat cost order),
// the others after them; the count kept; bad settings and penalties rejected.
#include "occlude/planner/seat_ranking.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace occlude::planner {
namespace {

// Seat i: contact, feasibility, and an id in basin (the penalty a judge reads from it).
GlobalProposal Seat(int id, double contact_mm2, bool feasible = true) {
  GlobalProposal s;
  s.basin = id;
  s.proposal.evaluation.contact_area_mm2 = contact_mm2;
  s.proposal.evaluation.feasible = feasible;
  return s;
}

std::vector<int> Ids(const std::vector<GlobalProposal>& seats) {
  std::vector<int> ids;
  for (const auto& s : seats) ids.push_back(s.basin);
  return ids;
}

// Seats in seat cost order: 0 (30 mm2), 1 (10), 2 (24), 3 (20), 4 (infeasible, 40).
std::vector<GlobalProposal> Seats() {
  return {Seat(0, 30.0), Seat(1, 10.0), Seat(2, 24.0), Seat(3, 20.0), Seat(4, 40.0, false)};
}

// Penalty per id: prefers 3, then 2 and 1 (equal), then 0; 4 lowest of all but infeasible.
SeatJudgement ByTable(const GlobalProposal& s) {
  const double penalty[] = {3.0, 1.0, 1.0, 0.5, 0.0};
  SeatJudgement j;
  j.penalty = penalty[s.basin];
  j.note = "seat " + std::to_string(s.basin);
  return j;
}

TEST(RankSeatsTest, WithoutAJudgeKeepsTheOrder) {
  const RankedSeats r = RankSeats(Seats(), {}, 10);
  EXPECT_EQ(Ids(r.proposals), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(r.excluded.empty());
  EXPECT_EQ(Ids(RankSeats(Seats(), {}, 2).proposals), (std::vector<int>{0, 1}));
}

TEST(RankSeatsTest, ComparableSeatsByPenaltyThenTheRestThenInfeasible) {
  SeatRanking ranking;
  ranking.judge = ByTable;
  ranking.comparable_contact = 0.5;  // floor 15 mm2 of the best feasible 30: seat 1 is below
  const RankedSeats r = RankSeats(Seats(), ranking, 10);
  EXPECT_EQ(Ids(r.proposals), (std::vector<int>{3, 2, 0, 1, 4}));
  EXPECT_EQ(r.proposals.front().judgement.note, "seat 3");
  ranking.comparable_contact = 0.0;  // every feasible seat competes; 2 and 1 tie: input order
  EXPECT_EQ(Ids(RankSeats(Seats(), ranking, 10).proposals), (std::vector<int>{3, 1, 2, 0, 4}));
  ranking.comparable_contact = 1.0;  // only the largest contact is in the first tier
  EXPECT_EQ(Ids(RankSeats(Seats(), ranking, 10).proposals), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(Ids(RankSeats(Seats(), ranking, 2).proposals), (std::vector<int>{0, 1}));
}

// c2-ios's pattern: the seat of the reference (depth 16, 30 mm^2, penalty 5: its overjet) and
// a seat 2.3 mm away with 60 % of its contact but 40 % of its depth (penalty 3.4: one class
// and less overjet); a third seat with 62 % of the depth competes (the synthetic pair's
// full-cusp Class II seat has 62 %).
TEST(RankSeatsTest, AShallowSeatDoesNotCompeteOnThePenalty) {
  auto seat = [](int id, double mm2, double depth) {
    GlobalProposal s = Seat(id, mm2);
    s.seat_depth = depth;
    return s;
  };
  const std::vector<GlobalProposal> seats = {seat(0, 30.0, 16.0), seat(1, 18.0, 6.4),
                                             seat(2, 20.0, 9.9)};
  SeatRanking ranking;
  ranking.judge = [](const GlobalProposal& s) {
    const double penalty[] = {5.0, 3.4, 4.0};
    return SeatJudgement{true, penalty[s.basin], ""};
  };
  EXPECT_EQ(ranking.comparable_depth, 0.55);
  EXPECT_EQ(Ids(RankSeats(seats, ranking, 10).proposals), (std::vector<int>{2, 0, 1}));
  ranking.comparable_depth = 0.0;  // by contact alone every seat competes
  EXPECT_EQ(Ids(RankSeats(seats, ranking, 10).proposals), (std::vector<int>{1, 2, 0}));
  ranking.comparable_depth = 0.7;  // only the seat of the reference is deep enough
  EXPECT_EQ(Ids(RankSeats(seats, ranking, 10).proposals), (std::vector<int>{0, 1, 2}));
  // Depths unknown (0 everywhere, as in Seats()): the contact floor alone, as before the depth.
  ranking.judge = ByTable;  // Seats() has ids 0-4; the table above covers 0-2 only
  ranking.comparable_depth = 0.55;
  ranking.comparable_contact = 0.5;
  SeatRanking by_contact_alone = ranking;
  by_contact_alone.comparable_depth = 0.0;
  EXPECT_EQ(Ids(RankSeats(Seats(), ranking, 10).proposals),
            Ids(RankSeats(Seats(), by_contact_alone, 10).proposals));
  EXPECT_EQ(Ids(RankSeats(Seats(), ranking, 10).proposals), (std::vector<int>{3, 2, 0, 1, 4}));
}

// c4-ios's pattern: the seat of the reference refined 0.1 mm above its bottom (1 mm^2 of
// contact in the band, depth 10.3, penalty 0.48) and a seat 1.3 mm away with one Class III
// molar (14.6 mm^2, depth 9.1, penalty 2.0). By default the contact area sets no seat aside:
// both compete on the penalty; a contact share of 0.5 would rank the worse seat first.
TEST(RankSeatsTest, TheContactAreaAloneSetsNoSeatAsideByDefault) {
  auto seat = [](int id, double mm2, double depth) {
    GlobalProposal s = Seat(id, mm2);
    s.seat_depth = depth;
    return s;
  };
  const std::vector<GlobalProposal> seats = {seat(0, 1.0, 10.3), seat(1, 14.6, 9.1)};
  SeatRanking ranking;
  ranking.judge = [](const GlobalProposal& s) {
    return SeatJudgement{true, s.basin == 0 ? 0.48 : 2.02, ""};
  };
  EXPECT_EQ(ranking.comparable_contact, 0.0);
  EXPECT_EQ(Ids(RankSeats(seats, ranking, 10).proposals), (std::vector<int>{0, 1}));
  ranking.comparable_contact = 0.5;
  EXPECT_EQ(Ids(RankSeats(seats, ranking, 10).proposals), (std::vector<int>{1, 0}));
}

TEST(RankSeatsTest, HardConstraintsSetSeatsAside) {
  SeatRanking ranking;
  ranking.judge = [](const GlobalProposal& s) {
    SeatJudgement j = ByTable(s);
    j.admissible = s.basin != 3 && s.basin != 0;
    return j;
  };
  const RankedSeats r = RankSeats(Seats(), ranking, 10);
  // Seats 1 and 2 have equal penalties: the seat cost order.
  EXPECT_EQ(Ids(r.proposals), (std::vector<int>{1, 2, 4}));
  EXPECT_EQ(Ids(r.excluded), (std::vector<int>{0, 3}));
  for (const auto& s : r.excluded) EXPECT_FALSE(s.judgement.admissible);
  // With a contact floor, from the best admissible feasible contact (24 mm2, floor 12): seat 1
  // falls below it.
  ranking.comparable_contact = 0.5;
  EXPECT_EQ(Ids(RankSeats(Seats(), ranking, 10).proposals), (std::vector<int>{2, 1, 4}));
}

TEST(RankSeatsTest, RejectsBadSettingsAndPenalties) {
  SeatRanking ranking;
  ranking.comparable_contact = 1.5;
  EXPECT_THROW(ValidateSeatRanking(ranking), std::invalid_argument);
  try {
    RankSeats(Seats(), ranking, 4);
    ADD_FAILURE() << "accepted comparable_contact 1.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("SeatRanking.comparable_contact"), std::string::npos);
  }
  ranking = {};
  for (const double bad : {-0.1, 1.1, std::numeric_limits<double>::quiet_NaN()}) {
    ranking.comparable_depth = bad;
    try {
      ValidateSeatRanking(ranking);
      ADD_FAILURE() << "accepted comparable_depth " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("SeatRanking.comparable_depth"), std::string::npos);
    }
  }
  ranking = {};
  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    ranking.judge = [bad](const GlobalProposal&) { return SeatJudgement{true, bad, ""}; };
    try {
      RankSeats(Seats(), ranking, 4);
      ADD_FAILURE() << "accepted penalty " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("seat 0"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace occlude::planner
