// colag_bench: measurements of the whole system. Modes:
//   colag_bench scheduler --instance FILE|DIR [--variant closed|open|deadline] [--work W]
//                         [--steps S]       the UAV's scheduler on TSPTW instances (standard
//                                           matrix format): the tour, or gaps per size
//   colag_bench tables [--seeds K] [--jobs J] [--table 1|2|3|4|all] [--csv FILE] [--quick]
//   colag_bench safety [--seeds K] [--jobs J] [--csv FILE] [--quick]
//                                           the paper's Table I and II, measured
//   colag_bench speed [--runs N] [--scenario S] [--ugvs N] [--seed S] [--world W]
//                     [--baseline COLAG_SIM]
//                                           the real-time factor of one mission, N times
#include <CLI/CLI.hpp>

#include "bench_safety.hpp"
#include "bench_scheduler.hpp"
#include "bench_speed.hpp"
#include "bench_tables.hpp"
#include "colag/common/limits.hpp"
#include "colag/sim/host_program.hpp"
#include "colag/uav/scheduler.hpp"

using namespace colag;

namespace {

int run(int argc, char** argv) {
  CLI::App app{"colag_bench: ColAG-fw measurements"};
  app.require_subcommand(1);
  auto* sched = app.add_subcommand(
      "scheduler", "the UAV's scheduler on a TSPTW instance, or on every instance in a directory");
  programs::SchedulerBenchOptions hopt;
  sched
      ->add_option("--instance", hopt.instance,
                   "TSPTW file (N, N x N matrix, N lines 'ready due') or a directory of them")
      ->required();
  sched
      ->add_option("--variant", hopt.variant,
                   "closed (the published tour), open (no way home), deadline (open, no ready)")
      ->check(CLI::IsMember({"closed", "open", "deadline"}));
  sched
      ->add_option("--exact-max", hopt.exact_max,
                   "largest instance solved exactly (0: heuristic only)")
      ->check(CLI::Range(0, uav::kExactMaxStops));
  sched->add_option("--work", hopt.work, "heuristic work budget per step (default: firmware's)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  sched->add_option("--steps", hopt.steps, "solves of each instance, each warm-started (anytime)")
      ->check(CLI::Range(1, 10000));
  sched->add_option("--seed", hopt.seed, "seed of the search's kicks (default: the firmware's)");
  sched->add_option("--best-known", hopt.best_known,
                    "CSV of published values (default: best_known.csv beside the instances)");
  sched
      ->add_option("--reference-runs", hopt.reference_runs,
                   "open/deadline: long runs (100 warm steps each) whose best is the reference")
      ->check(CLI::Range(0, 100));
  sched->add_option("--reference-out", hopt.reference_out,
                    "write each instance's reference (best_known.csv's layout)");
  sched->add_flag("--exact-reference", hopt.exact_reference,
                  "deadline variant, n <= 20: measure against the optimum (dynamic programming)");
  sched->add_option("--max-stops", hopt.max_stops, "skip a directory's larger instances")
      ->check(CLI::Range(1, 1 << 30));
  sched
      ->add_option("--max-mean-gap", hopt.max_mean_gap_pct,
                   "exit 1 if any size's mean gap (%) is above this or a tour is infeasible")
      ->check(CLI::Range(0.0, 1000.0));
  auto* tables = app.add_subcommand(
      "tables",
      "run the paper's Table I and II, Table III (several UAVs, scouting) and Table IV (how many "
      "UGVs K UAVs serve; both beyond the paper): missions over seeds, in parallel");
  programs::TablesOptions topt;
  tables->add_option("--seeds", topt.seeds, "seeds per configuration")->check(CLI::Range(1, 100));
  tables->add_option("--jobs", topt.jobs, "missions at once")->check(CLI::Range(1, 64));
  tables->add_option("--table", topt.tables, "1, 2, 3, 4 or all")
      ->check(CLI::IsMember({"1", "2", "3", "4", "all"}));
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
  safety
      ->add_option("--ugvs", sopt.ugvs,
                   "UGV counts flown on every map (default 3 5 7, pillars 3 5 8)")
      ->check(CLI::Range(1, static_cast<int>(limits::kMaxUgvs)));
  auto* speed = app.add_subcommand(
      "speed", "the real-time factor of one mission (default dense, 7 UGVs, seed 1), N runs");
  programs::SpeedOptions popt;
  speed->add_option("--runs", popt.runs, "runs, one after the other")->check(CLI::Range(1, 100));
  speed->add_option("--scenario", popt.scenario, "sparse, dense, pillars or rooms")
      ->check(CLI::IsMember({"sparse", "dense", "pillars", "rooms"}));
  speed->add_option("--ugvs", popt.ugvs, "UGVs")
      ->check(CLI::Range(1, static_cast<int>(limits::kMaxUgvs)));
  speed->add_option("--seed", popt.seed, "seed")->check(CLI::Range(0, 2147483647));
  speed->add_option("--world", popt.world, "ideal, field, or a YAML scenario file");
  speed->add_option("--target", popt.target, "real-time factor the median should reach")
      ->check(sim::positive_up_to(1e6));
  speed->add_option("--sim", popt.sim, "colag_sim to run (default: next to colag_bench)");
  speed->add_option("--baseline", popt.baseline,
                    "another colag_sim to alternate with, run for run (A/B comparison)");
  if (const auto code = sim::parse_command_line(app, argc, argv)) return *code;
  if (*sched) return programs::run_scheduler_bench(hopt);
  if (*tables) return programs::run_tables(topt);
  if (*safety) return programs::run_safety(sopt);
  if (*speed) return programs::run_speed(popt);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  return colag::sim::guarded_main("colag_bench", 1, [&] { return run(argc, argv); });
}
