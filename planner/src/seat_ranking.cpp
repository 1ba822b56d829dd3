// RankSeats(): the caller's judge over the distinct seats, the inadmissible
// ones set aside, the rest in tiers (feasible of comparable contact and seat
// depth, other feasible, infeasible) ordered by penalty within the first tier.
#include "occlude/planner/seat_ranking.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace occlude::planner {

void ValidateSeatRanking(const SeatRanking& ranking) {
  const double c = ranking.comparable_contact;
  if (!(std::isfinite(c) && c >= 0.0 && c <= 1.0)) {
    throw std::invalid_argument(
        "SeatRanking.comparable_contact: must be a share in [0, 1] of the best seat's contact "
        "area (default 0.5)");
  }
  const double d = ranking.comparable_depth;
  if (!(std::isfinite(d) && d >= 0.0 && d <= 1.0)) {
    throw std::invalid_argument(
        "SeatRanking.comparable_depth: must be a share in [0, 1] of the deepest seat's depth "
        "(default 0.55; 0 turns it off)");
  }
}

namespace {

// Judges every seat; throws for a penalty the ranking cannot compare.
void Judge(const SeatJudge& judge, std::vector<GlobalProposal>* seats) {
  for (std::size_t i = 0; i < seats->size(); ++i) {
    GlobalProposal& seat = (*seats)[i];
    seat.judgement = judge(seat);
    const double p = seat.judgement.penalty;
    if (!(std::isfinite(p) && p >= 0.0)) {
      throw std::invalid_argument("SeatRanking.judge: seat " + std::to_string(i) + " got penalty " +
                                  std::to_string(p) + "; a penalty must be finite and >= 0");
    }
  }
}

// The floors of the first tier: contact area and seat depth.
struct Floors {
  double mm2 = 0.0, depth = 0.0;
};

// 0: feasible with contact and depth at their floors, 1: other feasible, 2: infeasible.
int Tier(const GlobalProposal& seat, const Floors& floors) {
  const PoseEvaluation& e = seat.proposal.evaluation;
  if (!e.feasible) return 2;
  return e.contact_area_mm2 >= floors.mm2 && seat.seat_depth >= floors.depth ? 0 : 1;
}

}  // namespace

RankedSeats RankSeats(std::vector<GlobalProposal> seats, const SeatRanking& ranking,
                      int max_count) {
  ValidateSeatRanking(ranking);
  RankedSeats out;
  if (ranking.judge) Judge(ranking.judge, &seats);
  double best_mm2 = 0.0, best_depth = 0.0;
  for (GlobalProposal& seat : seats) {
    if (!seat.judgement.admissible) {
      out.excluded.push_back(std::move(seat));
      continue;
    }
    if (seat.proposal.evaluation.feasible) {
      best_mm2 = std::max(best_mm2, seat.proposal.evaluation.contact_area_mm2);
      best_depth = std::max(best_depth, seat.seat_depth);
    }
    out.proposals.push_back(std::move(seat));
  }
  if (ranking.judge) {
    const Floors floors{ranking.comparable_contact * best_mm2,
                        ranking.comparable_depth * best_depth};
    // Within a tier the input order is the seat cost order; the penalty counts in tier 0.
    std::stable_sort(out.proposals.begin(), out.proposals.end(),
                     [&floors](const GlobalProposal& a, const GlobalProposal& b) {
                       const int ta = Tier(a, floors), tb = Tier(b, floors);
                       if (ta != tb) return ta < tb;
                       return ta == 0 && a.judgement.penalty < b.judgement.penalty;
                     });
  }
  if (out.proposals.size() > static_cast<std::size_t>(std::max(0, max_count)))
    out.proposals.resize(static_cast<std::size_t>(std::max(0, max_count)));
  return out;
}

}  // namespace occlude::planner
