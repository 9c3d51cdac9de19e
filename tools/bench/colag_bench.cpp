// colag_bench: measurements of the whole system. Modes:
//   colag_bench scheduler --instance FILE   solve a TSPTW instance (standard matrix format)
//                                           with the UAV's scheduler and print the tour
//   colag_bench tables [--seeds K] [--jobs J] [--table 1|2|all] [--csv FILE] [--quick]
//   colag_bench safety [--seeds K] [--jobs J] [--csv FILE] [--quick]
//                                           the paper's Table I and II, measured
//   colag_bench speed [--runs N] [--scenario S] [--ugvs N] [--seed S] [--baseline COLAG_SIM]
//                                           the real-time factor of one mission, N times
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>

#include "bench_safety.hpp"
#include "bench_speed.hpp"
#include "bench_tables.hpp"
#include "colag/common/limits.hpp"
#include "colag/sim/host_program.hpp"
#include "tsptw_instance.hpp"

using namespace colag;

namespace {

int run_scheduler(const std::string& path, int exact_max) {
  auto problem = std::make_unique<uav::ScheduleProblem>();
  std::string error;
  if (!programs::read_tsptw(path, *problem, error)) {
    std::fprintf(stderr, "colag_bench scheduler: %s\n", error.c_str());
    return 2;
  }
  uav::SchedulerConfig cfg;
  cfg.exact_max_stops = exact_max;
  auto scheduler = std::make_unique<uav::Scheduler>(cfg);
  const auto t0 = std::chrono::steady_clock::now();
  const uav::ScheduleResult& r = scheduler->solve(*problem);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("instance   %s (%d customers)\n", path.c_str(), problem->n);
  std::printf("tour       0");
  for (const auto k : r.order)
    std::printf(" %d", k);
  std::printf(" 0\n");
  std::printf("travel     %.3f\n", r.cost.travel_s);
  std::printf("feasible   %s (total lateness %.3f)\n", r.cost.feasible ? "yes" : "no",
              r.cost.lateness_s);
  std::printf("optimal    %s\n", r.exact ? "proven" : "not proven (heuristic)");
  std::printf("time       %.3f ms\n", ms);
  return 0;
}

int run(int argc, char** argv) {
  CLI::App app{"colag_bench: ColAG-fw measurements"};
  app.require_subcommand(1);
  auto* sched = app.add_subcommand("scheduler", "solve a TSPTW instance with the UAV's scheduler");
  std::string instance;
  int exact_max = uav::kExactMaxStops;
  sched->add_option("--instance", instance, "TSPTW file: N, N x N matrix, N lines 'ready due'")
      ->required();
  sched->add_option("--exact-max", exact_max, "largest instance solved exactly (0: heuristic only)")
      ->check(CLI::Range(0, uav::kExactMaxStops));
  auto* tables = app.add_subcommand(
      "tables", "run the paper's Table I and II (missions over seeds, in parallel)");
  programs::TablesOptions topt;
  tables->add_option("--seeds", topt.seeds, "seeds per configuration")->check(CLI::Range(1, 100));
  tables->add_option("--jobs", topt.jobs, "missions at once")->check(CLI::Range(1, 64));
  tables->add_option("--table", topt.tables, "1, 2 or all")
      ->check(CLI::IsMember({"1", "2", "all"}));
  tables->add_option("--csv", topt.csv, "per-mission results");
  tables->add_option("--max-time", topt.max_time_s, "simulated seconds per mission")
      ->check(sim::positive_up_to(1e6));
  tables->add_option("--sim", topt.sim, "colag_sim to run (default: next to colag_bench)");
  tables->add_flag("--quick", topt.quick, "one small configuration, one seed (a smoke run)");
  tables->add_option("--world", topt.world, "ideal (the paper's), field, or a YAML scenario file");
  auto* safety = app.add_subcommand(
      "safety", "Monte-Carlo under faults: maps x UGV counts x fault settings x seeds");
  programs::SafetyOptions sopt;
  safety->add_option("--seeds", sopt.seeds, "seeds per configuration")->check(CLI::Range(1, 100));
  safety->add_option("--jobs", sopt.jobs, "missions at once")->check(CLI::Range(1, 64));
  safety->add_option("--csv", sopt.csv, "per-mission results");
  safety->add_option("--max-time", sopt.max_time_s, "simulated seconds per mission")
      ->check(sim::positive_up_to(1e6));
  safety->add_option("--sim", sopt.sim, "colag_sim to run (default: next to colag_bench)");
  safety->add_flag("--quick", sopt.quick, "dense, 3 UGVs, two fault settings, one seed");
  safety->add_option("--world", sopt.world, "ideal, field, or a YAML scenario file");
  auto* speed = app.add_subcommand(
      "speed", "the real-time factor of one mission (default dense, 7 UGVs, seed 1), N runs");
  programs::SpeedOptions popt;
  speed->add_option("--runs", popt.runs, "runs, one after the other")->check(CLI::Range(1, 100));
  speed->add_option("--scenario", popt.scenario, "sparse, dense, pillars or rooms")
      ->check(CLI::IsMember({"sparse", "dense", "pillars", "rooms"}));
  speed->add_option("--ugvs", popt.ugvs, "UGVs")
      ->check(CLI::Range(1, static_cast<int>(limits::kMaxUgvs)));
  speed->add_option("--seed", popt.seed, "seed")->check(CLI::Range(0, 2147483647));
  speed->add_option("--target", popt.target, "real-time factor the median should reach")
      ->check(sim::positive_up_to(1e6));
  speed->add_option("--sim", popt.sim, "colag_sim to run (default: next to colag_bench)");
  speed->add_option("--baseline", popt.baseline,
                    "another colag_sim to alternate with, run for run (A/B comparison)");
  if (const auto code = sim::parse_command_line(app, argc, argv)) return *code;
  if (*sched) return run_scheduler(instance, exact_max);
  if (*tables) return programs::run_tables(topt);
  if (*safety) return programs::run_safety(sopt);
  if (*speed) return programs::run_speed(popt);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  return colag::sim::guarded_main("colag_bench", 1, [&] { return run(argc, argv); });
}
