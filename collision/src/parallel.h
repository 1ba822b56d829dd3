// Threads for the builds (private to collision): a thread count resolved against the machine,
// a loop over numbered items run by a few workers, and independent tasks run concurrently.
//
// Determinism is the callers' contract: every item's result may depend only on the item (its
// number and the inputs), never on which worker runs it, in which order, or how many workers
// there are; items are fixed by the caller (e.g. blocks of a constant size), so results are
// bit-identical for any thread count. The standard library is enough here: the parallel work
// is a handful of coarse stages and a few loops of equal items, on machines of a few cores.
//
// Exceptions: once an item or task throws, no new one starts; after all workers have stopped,
// the exception of the lowest-numbered failed item (or task) is rethrown on the calling thread.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace occlude::collision::detail {

/// `requested` threads, 0 meaning every core (std::thread::hardware_concurrency, at least 1).
/// Throws std::invalid_argument for a negative count.
int ResolveThreads(int requested);

/// Calls body(item, worker) for every item in [0, count), on min(threads, count) workers
/// (the calling thread is worker 0; worker < that number, so callers can keep scratch space
/// per worker). threads >= 1 (ResolveThreads).
void ParallelFor(std::size_t count, int threads,
                 const std::function<void(std::size_t item, int worker)>& body);

/// Runs every task, up to `threads` at a time (the calling thread runs some of them); returns
/// when all have finished.
void RunConcurrently(int threads, const std::vector<std::function<void()>>& tasks);

}  // namespace occlude::collision::detail
