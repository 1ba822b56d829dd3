// Ranking the global search's distinct seats by a clinical judgement the caller
// supplies (the app's arch analysis measures the relationships at each seat:
// molar and canine class, overjet, overbite, midline). The planner knows no
// clinical measure: a judge gives each seat a hard verdict (admissible or not:
// the hard constraints) and a ranking penalty (the ranking terms), and the
// ranking orders the seats by contact tier, then penalty. GlobalSearch ranks
// with the request's judge; the app may call RankSeats again on a result's
// seats with other targets without searching again.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "occlude/planner/arch_alignment.h"
#include "occlude/planner/plan.h"

namespace occlude::planner {

/// The caller's judgement of one seat.
struct SeatJudgement {
  /// False when the seat breaks a hard constraint: it leaves the proposals (RankedSeats::
  /// excluded keeps it).
  bool admissible = true;
  /// Ranking terms (>= 0, finite; lower is better), compared among seats of comparable contact.
  double penalty = 0.0;
  std::string note;  ///< e.g. "molar I/I, canine I/II, overjet 2.7 mm" (shown, not parsed)
};

/// One distinct seat of the global search.
struct GlobalProposal {
  Proposal proposal;  ///< its params relative to the aligned pose about the pivot
  ArchShift from_aligned;
  ArchShift from_given;     ///< from the request's local.X_LU_start
  int basin = 0;            ///< index into GlobalResult::basins it was refined from
  SeatJudgement judgement;  ///< the ranking's verdict (the default one without a judge)
};

/// The judge: called once per distinct seat, serialized, in the order of the seats as found
/// (feasible first, lowest seat cost first). It must be deterministic for deterministic results.
using SeatJudge = std::function<SeatJudgement(const GlobalProposal& seat)>;

struct SeatRanking {
  SeatJudge judge;  ///< empty: the seats keep their order (seat cost), all admissible
  /// Feasible admissible seats whose contact area is at least this share of the largest among
  /// them compete on the penalty (ties by seat cost); the rest follow by seat cost, then the
  /// infeasible ones. In [0, 1]: 0 ranks every feasible seat by penalty, 1 only the best.
  double comparable_contact = 0.5;
};

/// Throws std::invalid_argument naming the field ("SeatRanking.comparable_contact") and the fix.
void ValidateSeatRanking(const SeatRanking& ranking);

struct RankedSeats {
  std::vector<GlobalProposal> proposals;  ///< ranked as SeatRanking says, at most max_count
  std::vector<GlobalProposal> excluded;   ///< inadmissible seats, in their input order
};

/// Judges `seats` (distinct, in the order GlobalSearch finds them), drops the inadmissible ones
/// and ranks the rest (a stable order: equal keys keep their input order), keeping at most
/// `max_count`. Each seat's GlobalProposal::judgement holds its verdict. Throws
/// std::invalid_argument for an invalid ranking or a judgement with a negative or non-finite
/// penalty (naming the seat).
RankedSeats RankSeats(std::vector<GlobalProposal> seats, const SeatRanking& ranking, int max_count);

}  // namespace occlude::planner
