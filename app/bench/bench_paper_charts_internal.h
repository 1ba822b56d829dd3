// The charts of `occlude bench --paper`: Figs. 4, 5, 7, 8 against the voxel
// size, Fig. 9 per level, Fig. 10 against the offset (names and PNG bytes).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bench/bench_paper.h"

namespace occlude::app {

std::vector<std::pair<std::string, std::string>> PaperCharts(const PaperResult& result,
                                                             const std::string& machine);

}  // namespace occlude::app
