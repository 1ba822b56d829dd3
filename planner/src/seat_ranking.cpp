// RankSeats(): the caller's judge over the distinct seats, the inadmissible
// ones set aside, the rest in tiers (feasible of comparable contact, other
// feasible, infeasible) ordered by penalty within the first tier.
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

// 0: feasible with contact >= floor_mm2, 1: other feasible, 2: infeasible.
int Tier(const GlobalProposal& seat, double floor_mm2) {
  const PoseEvaluation& e = seat.proposal.evaluation;
  if (!e.feasible) return 2;
  return e.contact_area_mm2 >= floor_mm2 ? 0 : 1;
}

}  // namespace

RankedSeats RankSeats(std::vector<GlobalProposal> seats, const SeatRanking& ranking,
                      int max_count) {
  ValidateSeatRanking(ranking);
  RankedSeats out;
  if (ranking.judge) Judge(ranking.judge, &seats);
  double best_mm2 = 0.0;
  for (GlobalProposal& seat : seats) {
    if (!seat.judgement.admissible) {
      out.excluded.push_back(std::move(seat));
      continue;
    }
    if (seat.proposal.evaluation.feasible)
      best_mm2 = std::max(best_mm2, seat.proposal.evaluation.contact_area_mm2);
    out.proposals.push_back(std::move(seat));
  }
  if (ranking.judge) {
    const double floor_mm2 = ranking.comparable_contact * best_mm2;
    // Within a tier the input order is the seat cost order; the penalty counts in tier 0.
    std::stable_sort(out.proposals.begin(), out.proposals.end(),
                     [floor_mm2](const GlobalProposal& a, const GlobalProposal& b) {
                       const int ta = Tier(a, floor_mm2), tb = Tier(b, floor_mm2);
                       if (ta != tb) return ta < tb;
                       return ta == 0 && a.judgement.penalty < b.judgement.penalty;
                     });
  }
  if (out.proposals.size() > static_cast<std::size_t>(std::max(0, max_count)))
    out.proposals.resize(static_cast<std::size_t>(std::max(0, max_count)));
  return out;
}

}  // namespace occlude::planner
