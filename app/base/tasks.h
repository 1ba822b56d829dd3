// Independent tasks on a few threads, for the commands' steps that can overlap (the report's
// images, the two jaws' analyses, the 3D view's decimation beside a pose's analysis).
#pragma once

#include <functional>
#include <vector>

namespace occlude::app {

/// Runs every task once on up to `threads` threads (the calling one among them), each thread
/// taking the next task left in order, so the slowest should come first. Returns when all
/// have run; then rethrows the exception of the first failed task (by position), if any.
void RunTasks(const std::vector<std::function<void()>>& tasks, int threads = 2);

}  // namespace occlude::app
