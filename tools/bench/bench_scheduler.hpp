#pragma once
// colag_bench scheduler: the UAV's scheduler on TSPTW instances in the standard matrix format.
// One file prints the tour; a directory runs every instance in it and prints, per instance and
// per size, the gap to a reference, feasibility, work and time.
// Variants (the files are read as they are and changed in memory only):
//   closed    the published problem: a tour back to the depot (reference: best_known.csv
//             beside the instances, published optima)
//   open      no return arc (the UAV does not go home between requests)
//   deadline  open, and ready times dropped: the UAV's own problem
// Open and deadline optima are not published: their reference is the best tour found by
// `reference_runs` long runs (reported as such, not as an optimum).
#include <cstdint>
#include <string>

namespace colag::programs {

struct SchedulerBenchOptions {
  std::string instance;  // a file or a directory of *.txt instances
  std::string variant = "closed";
  int exact_max = -1;            // -1: the scheduler's default
  std::uint64_t work = 0;        // work budget per step (0: the scheduler's default)
  int steps = 1;                 // anytime: solves of the same problem, each warm-started
  std::uint64_t seed = 0;        // of the search's kicks (0: the firmware's)
  std::string best_known;        // CSV (default: best_known.csv beside the instances)
  int reference_runs = 0;        // open/deadline: long runs that give the reference (0: none)
  std::string reference_out;     // writes each instance's reference there (CSV)
  bool exact_reference = false;  // deadline variant, n <= 20: the optimum by dynamic programming
  double max_mean_gap_pct = -1;  // exit 1 if a size's mean gap exceeds it (< 0: no check)
  int max_stops = 1 << 30;       // a directory's instances with more stops are skipped
};

// Exit codes: 0 done (and within --max-mean-gap), 1 a gap or feasibility target missed,
// 2 bad input.
int run_scheduler_bench(const SchedulerBenchOptions& options);

}  // namespace colag::programs
