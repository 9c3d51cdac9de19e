#include "bench_safety.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "mission_pool.hpp"

namespace colag::programs {

namespace {

struct FaultSetting {
  const char* name;
  std::vector<std::string> args;
};

const std::vector<FaultSetting>& settings() {
  static const std::vector<FaultSetting> all = {
      {"none", {}},
      {"loss30+lat300", {"--loss", "30", "--latency-ms", "300"}},
      {"loss20+jit200", {"--loss", "20", "--latency-ms", "100", "--jitter-ms", "200"}},
      {"uav-blackout20s", {"--uav-blackout", "20:40"}},
      {"all-blackout10s", {"--blackout", "20:30"}},
      {"rpe-blackout30s", {"--rpe-blackout", "15:45"}},
      {"odom-bias3%", {"--odom-bias", "3"}},
      // Clocks an hour apart drifting 50 ppm, and fleet time (UAV 0's clock) stepping 2 s.
      {"clocks1h+step2s",
       {"--clock-offset-s", "3600", "--clock-drift-ppm", "50", "--clock-step", "30:2"}},
      // UGV 0's firmware dies at 25 s and starts again 5 s later, knowing only its configuration
      // (UGV 0: every fleet has one).
      {"ugv0-restart", {"--kill-ugv", "0@25", "--restart-after", "5"}},
  };
  return all;
}

}  // namespace

int run_safety(const SafetyOptions& o) {
  std::vector<MissionRun> runs;
  for (const FaultSetting& f : settings()) {
    if (o.quick && std::string(f.name) != "loss30+lat300" &&
        std::string(f.name) != "uav-blackout20s")
      continue;
    // The paper's two maps, and a field of taller, thinner pillars of several sizes.
    for (const char* scen : {"sparse", "dense", "pillars"}) {
      const bool pillars = std::string(scen) == "pillars";
      const std::vector<int> counts =
          o.ugvs.empty() ? std::vector<int>{3, 5, pillars ? 8 : 7} : o.ugvs;
      for (const int n : counts) {
        if (o.quick && (std::string(scen) != "dense" || n != 3)) continue;
        for (int s = 1; s <= (o.quick ? 1 : o.seeds); ++s) {
          MissionRun r;
          r.spec.scenario = scen;
          r.spec.ugvs = n;
          r.spec.faults = f.name;
          r.spec.fault_args = f.args;
          r.spec.world = o.world;
          r.seed = s;
          runs.push_back(r);
        }
      }
    }
  }
  std::printf("colag_bench safety: %zu missions in the %s world, %d at a time\n", runs.size(),
              o.world.c_str(), o.jobs);
  if (!run_missions(runs, sim_path(o.sim), o.jobs, o.max_time_s)) return 2;

  std::ofstream csv(o.csv);
  csv << "faults,scenario,ugvs,seed,ok,all_reached,collisions,reached_ugvs,min_clearance_m,"
         "reach_time_s,waiting_time_s,max_waiting_time_s,nees_min_ugv,nees_max_ugv\n";
  std::string sizes = "sparse+dense x 3/5/7 UGVs, pillars x 3/5/8";
  if (!o.ugvs.empty()) {
    sizes = "sparse+dense+pillars x ";
    for (std::size_t i = 0; i < o.ugvs.size(); ++i)
      sizes += (i > 0 ? "/" : "") + std::to_string(o.ugvs[i]);
    sizes += " UGVs";
  }
  std::printf("\nSafety under faults (maps %s, x seeds):\n", sizes.c_str());
  std::printf("%-16s %8s %10s %12s %14s %9s %8s %8s %12s\n", "faults", "missions", "collisions",
              "UGVs reached", "min clear. m", "reach s", "wait s", "max wait", "NEES in 1-6");
  int failed = 0, total_collisions = 0;
  for (const FaultSetting& f : settings()) {
    int missions = 0, collisions = 0, reached = 0, ugvs = 0;
    int nees_ok = 0;  // UGVs whose mean NEES is within [1, 6] (3-dof: 3 is honest)
    double min_clearance = std::numeric_limits<double>::infinity(), max_wait = 0.0;
    Mean reach, wait;
    for (const MissionRun& r : runs) {
      if (r.spec.faults != f.name) continue;
      ++missions;
      csv << f.name << ',' << r.spec.scenario << ',' << r.spec.ugvs << ',' << r.seed << ',' << r.ok;
      if (!r.ok) {
        ++failed;
        csv << '\n';
        continue;
      }
      const auto& s = r.result["summary"];
      int mission_reached = 0;
      double mission_clearance = std::numeric_limits<double>::infinity();
      double nees_min = std::numeric_limits<double>::infinity(), nees_max = 0.0;
      for (const auto& u : r.result["ugvs"]) {
        ++ugvs;
        const double nees = u["nees_mean"].get<double>();
        nees_ok += nees >= 1.0 && nees <= 6.0 ? 1 : 0;
        nees_min = std::min(nees_min, nees);
        nees_max = std::max(nees_max, nees);
        mission_reached += u["reached"].get<bool>() ? 1 : 0;
        mission_clearance = std::min(mission_clearance, u["min_clearance_m"].get<double>());
      }
      reached += mission_reached;
      min_clearance = std::min(min_clearance, mission_clearance);
      collisions += s["collisions"].get<int>();
      if (!s["reach_time_s"].is_null()) reach.add(s["reach_time_s"].get<double>());
      wait.add(s["waiting_time_s"].get<double>());
      max_wait = std::max(max_wait, s["max_waiting_time_s"].get<double>());
      csv << ',' << s["all_reached"].get<bool>() << ',' << s["collisions"].get<int>() << ','
          << mission_reached << ',' << mission_clearance << ','
          << (s["reach_time_s"].is_null() ? std::string()
                                          : std::to_string(s["reach_time_s"].get<double>()))
          << ',' << s["waiting_time_s"].get<double>() << ','
          << s["max_waiting_time_s"].get<double>() << ',' << nees_min << ',' << nees_max << '\n';
    }
    if (missions == 0) continue;
    total_collisions += collisions;
    std::printf("%-16s %8d %10d %7d/%-4d %14.3f %9.1f %8.1f %8.1f %7d/%-4d\n", f.name, missions,
                collisions, reached, ugvs, min_clearance, reach.get(), wait.get(), max_wait,
                nees_ok, ugvs);
  }
  std::printf("\ntotal collisions: %d;  per-mission CSV: %s\n", total_collisions, o.csv.c_str());
  if (failed > 0) std::printf("%d mission%s failed to run\n", failed, failed == 1 ? "" : "s");
  return failed > 0 ? 1 : 0;
}

}  // namespace colag::programs
