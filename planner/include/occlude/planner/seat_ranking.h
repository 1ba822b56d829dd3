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
  /// How far the seat objective drops from the jaws apart to this seat (the seat cost with no
  /// sample within the attraction window minus proposal.seat_cost, on the last stage's
  /// samples): how much occlusal surface the seat closes, robustly (unlike the contact area
  /// within the band). Larger is better; 0 when unknown.
  double seat_depth = 0.0;
};

/// The judge: called once per distinct seat, serialized, in the order of the seats as found
/// (feasible first, lowest seat cost first). It must be deterministic for deterministic results.
using SeatJudge = std::function<SeatJudgement(const GlobalProposal& seat)>;

struct SeatRanking {
  SeatJudge judge;  ///< empty: the seats keep their order (seat cost), all admissible
  /// Feasible admissible seats whose contact area is at least this share of the largest among
  /// them, and whose seat depth at least comparable_depth of the deepest among them, compete
  /// on the penalty (ties by seat cost); the rest follow by seat cost, then the infeasible
  /// ones. In [0, 1]: 0 (the default) leaves it to the seat depth, 1 only the best. The
  /// contact area within the band is a hair trigger: on c4-ios the seat refined 0.1 mm above
  /// its bottom had 0.2-9 mm^2 against 14-24 mm^2 for points 0.6-1.7 mm away with a worse
  /// seat cost and penalty, which a share of 0.5 ranked first.
  double comparable_contact = 0.0;
  /// The same share of GlobalProposal::seat_depth (0 turns it off; seats of depth 0, unknown,
  /// pass when the deepest is 0 too). The contact area within the band alone is a hair
  /// trigger: on c2-ios the seat of the reference (depth 15-16.5, 14-31 mm^2) lost to seats of
  /// depth 5.4-8.0 with 55-86 % of its contact area; the full-cusp Class II seat of the
  /// synthetic pair has 62 % of the designed bite's depth (81 % of its contact).
  double comparable_depth = 0.55;
};

/// Throws std::invalid_argument naming the field ("SeatRanking.comparable_contact" or
/// "SeatRanking.comparable_depth") and the fix.
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
