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

// The mission's JSON without what the host's speed changes: same seed, same code => equal.
nlohmann::json mission_of(const MissionRun& r) {
  nlohmann::json j = r.result;
  j.erase("wall_time_s");
  j.erase("realtime_factor");
  return j;
}

double wall_of(const MissionRun& r) {
  return r.result.value("wall_time_s", 0.0);
}
double factor_of(const MissionRun& r) {
  return r.result.value("realtime_factor", 0.0);
}
}  // namespace

int run_speed(const SpeedOptions& o) {
  const bool ab = !o.baseline.empty();
  MissionRun proto;
  proto.spec.scenario = o.scenario;
  proto.spec.ugvs = o.ugvs;
  proto.spec.world = o.world;
  proto.seed = o.seed;
  std::vector<MissionRun> runs(static_cast<std::size_t>(o.runs), proto);
  std::vector<MissionRun> base(ab ? runs.size() : 0, proto);
  std::printf("real-time factor: %s, %d UGVs, seed %d, %s world, %d runs one after the other%s\n",
              o.scenario.c_str(), o.ugvs, o.seed, o.world.c_str(), o.runs,
              ab ? ", each after a run of the baseline" : "");
  const std::string sim = sim_path(o.sim);
  if (!ab) {
    if (!run_missions(runs, sim, 1, o.max_time_s)) return 2;
  } else {
    // Alternated, so that both binaries see the same drift of a shared machine's speed.
    for (std::size_t i = 0; i < runs.size(); ++i) {
      std::vector<MissionRun> one{base[i]};
      if (!run_missions(one, o.baseline, 1, o.max_time_s)) return 2;
      base[i] = one.front();
      one = {runs[i]};
      if (!run_missions(one, sim, 1, o.max_time_s)) return 2;
      runs[i] = one.front();
    }
  }

  std::vector<double> factors, walls, base_walls;
  bool all_ok = true, same = true, same_as_base = true;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const MissionRun& r = runs[i];
    all_ok = all_ok && r.ok && (!ab || base[i].ok);
    if (!r.ok) continue;
    factors.push_back(factor_of(r));
    walls.push_back(wall_of(r));
    same = same && runs.front().ok && mission_of(r) == mission_of(runs.front());
    if (ab && base[i].ok) {
      base_walls.push_back(wall_of(base[i]));
      same_as_base = same_as_base && mission_of(r) == mission_of(base[i]);
    }
  }
  std::printf(ab ? "\nrun   baseline wall s   wall s   simulated s   real-time factor\n"
                 : "\nrun   wall s   simulated s   real-time factor\n");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const MissionRun& r = runs[i];
    if (ab) {
      if (base[i].ok) {
        std::printf("%3zu   %15.2f   ", i + 1, wall_of(base[i]));
      } else {
        std::printf("%3zu   %15s   ", i + 1, "failed");
      }
    } else {
      std::printf("%3zu   ", i + 1);
    }
    if (!r.ok) {
      std::printf("failed\n");
      continue;
    }
    std::printf("%6.2f   %11.1f   %6.1fx\n", wall_of(r), r.result.value("sim_time_s", 0.0),
                factor_of(r));
  }
  if (factors.empty()) return 1;
  const double mid = median(factors);
  std::printf("\nmedian %.1fx, best %.1fx, worst %.1fx; target %.0fx: %s\n", mid,
              *std::max_element(factors.begin(), factors.end()),
              *std::min_element(factors.begin(), factors.end()), o.target,
              mid >= o.target ? "met" : "not met");
  std::printf("every run the same mission (JSON without the wall time): %s\n", same ? "yes" : "NO");
  if (ab && !base_walls.empty()) {
    const double b = median(base_walls), w = median(walls);
    std::printf("median wall time: baseline %.3f s, this %.3f s; this / baseline %.3f\n", b, w,
                w / b);
    std::printf("the same mission as the baseline: %s\n", same_as_base ? "yes" : "no");
  }
  return all_ok && same ? 0 : 1;
}

}  // namespace colag::programs
