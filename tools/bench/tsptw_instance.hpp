#pragma once
// Reads a TSPTW instance in the standard matrix text format used by the published benchmark
// sets (Dumas et al., Gendreau et al.): the number of nodes N, then the N x N travel-time
// matrix row by row, then N lines "ready due". Node 0 is the depot; the tour returns to it.
#include <string>

#include "colag/common/status.hpp"
#include "colag/uav/scheduler.hpp"

namespace colag::programs {

// On failure, `error` says what is wrong and where (line number).
bool read_tsptw(const std::string& path, uav::ScheduleProblem& out, std::string& error);

}  // namespace colag::programs
