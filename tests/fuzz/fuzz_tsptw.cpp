// TSPTW instances as `colag_bench scheduler --instance` reads them: parse_tsptw on arbitrary text,
// then the UAV's scheduler on what it accepts. Invariants: a refused text says why; an accepted
// one is in range (node count, finite non-negative bounded times, ready <= due) and the scheduler
// returns a tour of every customer with a finite cost.
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "fuzz_input.hpp"
#include "tsptw_instance.hpp"

using namespace colag;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  std::istringstream text(std::string(reinterpret_cast<const char*>(data), size));
  auto problem = std::make_unique<uav::ScheduleProblem>();
  std::string error;
  if (!programs::parse_tsptw(text, "fuzz.txt", *problem, error)) {
    COLAG_FUZZ_CHECK(error.rfind("fuzz.txt", 0) == 0);
    return 0;
  }
  const int n = problem->n;
  COLAG_FUZZ_CHECK(n >= 1 && n <= static_cast<int>(uav::kMaxStops));
  for (int i = 0; i <= n; ++i) {
    COLAG_FUZZ_CHECK(problem->ready[i] >= 0 && problem->ready[i] <= problem->due[i]);
    COLAG_FUZZ_CHECK(problem->due[i] <= programs::kMaxTsptwTime_s);
    for (int j = 0; j <= n; ++j) {
      const double t = problem->travel[i][j];
      COLAG_FUZZ_CHECK(t >= 0 && t <= programs::kMaxTsptwTime_s);
    }
  }
  uav::SchedulerConfig cfg;
  cfg.exact_max_stops = 8;  // exact search is exponential: keep each input fast
  auto scheduler = std::make_unique<uav::Scheduler>(cfg);
  const uav::ScheduleResult& r = scheduler->solve(*problem);
  COLAG_FUZZ_CHECK(static_cast<int>(r.order.size()) == n);
  COLAG_FUZZ_CHECK(std::isfinite(r.cost.travel_s) && std::isfinite(r.cost.lateness_s));
  return 0;
}
