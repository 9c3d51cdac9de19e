#pragma once
// Reads a TSPTW instance in the standard matrix text format used by the published benchmark
// sets (Dumas et al., Gendreau et al.): the number of nodes N, then the N x N travel-time
// matrix row by row, then N lines "ready due". Node 0 is the depot; the tour returns to it.
// Every number is checked: N in [2, kMaxStops + 1], travel times and windows finite, >= 0 and
// <= kMaxTime_s (so that no sum along a tour overflows), ready <= due.
#include <istream>
#include <string>

#include "colag/uav/scheduler.hpp"

namespace colag::programs {

inline constexpr double kMaxTsptwTime_s = 1e9;  // ~32 years: any real instance, and no overflow

// On failure, `error` says what is wrong and where ("NAME:LINE: problem").
bool read_tsptw(const std::string& path, uav::ScheduleProblem& out, std::string& error);
// The same from a stream; `path` stands for the file in errors.
bool parse_tsptw(std::istream& in, const std::string& path, uav::ScheduleProblem& out,
                 std::string& error);

}  // namespace colag::programs
