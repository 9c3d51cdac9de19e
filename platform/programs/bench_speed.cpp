#include "bench_speed.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "mission_pool.hpp"

namespace colag::programs {

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

int run_speed(const SpeedOptions& o) {
  MissionSpec spec;
  spec.scenario = o.scenario;
  spec.ugvs = o.ugvs;
  std::vector<MissionRun> runs(static_cast<std::size_t>(o.runs));
  for (MissionRun& r : runs) {
    r.spec = spec;
    r.seed = o.seed;
  }
  std::printf("real-time factor: %s, %d UGVs, seed %d, %d runs one after the other\n",
              o.scenario.c_str(), o.ugvs, o.seed, o.runs);
  if (!run_missions(runs, sim_path(o.sim), 1, o.max_time_s)) return 2;

  std::vector<double> factors;
  bool same = true;
  for (const MissionRun& r : runs) {
    if (!r.ok) continue;
    factors.push_back(r.result.value("realtime_factor", 0.0));
    // Same seed, same mission: everything but the wall time must agree.
    auto a = r.result, b = runs.front().result;
    for (auto* j : {&a, &b}) {
      j->erase("wall_time_s");
      j->erase("realtime_factor");
    }
    same = same && runs.front().ok && a == b;
  }
  std::printf("\nrun   wall s   simulated s   real-time factor\n");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const MissionRun& r = runs[i];
    if (!r.ok) {
      std::printf("%3zu   failed\n", i + 1);
      continue;
    }
    std::printf("%3zu   %6.2f   %11.1f   %6.1fx\n", i + 1, r.result.value("wall_time_s", 0.0),
                r.result.value("sim_time_s", 0.0), r.result.value("realtime_factor", 0.0));
  }
  if (factors.empty()) return 1;
  const double mid = median(factors);
  std::printf("\nmedian %.1fx, best %.1fx, worst %.1fx; target %.0fx: %s\n", mid,
              *std::max_element(factors.begin(), factors.end()),
              *std::min_element(factors.begin(), factors.end()), o.target,
              mid >= o.target ? "met" : "not met");
  std::printf("every run the same mission (JSON without the wall time): %s\n", same ? "yes" : "NO");
  return factors.size() == runs.size() && same ? 0 : 1;
}

}  // namespace colag::programs
