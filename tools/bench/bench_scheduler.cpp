#include "bench_scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "colag/uav/scheduler.hpp"
#include "tsptw_instance.hpp"

namespace colag::programs {

namespace {

namespace fs = std::filesystem;

struct Outcome {
  std::string name;
  int n = 0;
  double travel = 0;
  bool feasible = false;
  bool exact = false;
  double reference = -1;  // < 0: none
  bool reference_exact = false;
  double ms = 0;
  std::uint64_t work = 0;
};

void apply_variant(const std::string& variant, uav::ScheduleProblem& p) {
  if (variant == "closed") return;
  p.closed = false;
  if (variant == "deadline") {
    for (int k = 0; k <= p.n; ++k)
      p.ready[k] = 0.0;
  }
}

// best_known.csv: "Benchmark Set,Instance Name,Best Known Solution,..."; returns name -> value.
std::map<std::string, double> read_best_known(const std::string& path) {
  std::map<std::string, double> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ','))
      cells.push_back(cell);
    if (cells.size() < 3) continue;
    try {
      out[cells[1]] = std::stod(cells[2]);
    } catch (const std::exception&) {  // the header, or a cell that is not a number
    }
  }
  return out;
}

struct Solved {
  uav::ScheduleResult result;
  double ms = 0;
  std::uint64_t work = 0;
};

// `steps` solves of the same problem, each warm-started from the last plan (the anytime use).
Solved solve(const uav::ScheduleProblem& p, uav::SchedulerConfig cfg, int steps) {
  auto scheduler = std::make_unique<uav::Scheduler>(cfg);
  Solved s;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    const auto warm = s.result.order;
    s.result = scheduler->solve(p, {warm.begin(), warm.end()});
    s.work += scheduler->last_work();
  }
  s.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

// The deadline variant's optimum for n <= kExactDeadlineStops, by dynamic programming over
// subsets (Held-Karp): with no ready times nothing waits, so a path's arrival is its travel and
// one number per (visited set, last stop) is exact. Deadlines are hard. -1: no route meets them.
constexpr int kExactDeadlineStops = 20;  // 2^20 x 20 doubles: 168 MB, about a second
double exact_deadline_optimum(const uav::ScheduleProblem& p) {
  const int n = p.n;
  const std::size_t sets = std::size_t{1} << n;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> best(sets * static_cast<std::size_t>(n), inf);
  const auto at = [&](std::size_t set, int last) {
    return set * static_cast<std::size_t>(n) + static_cast<std::size_t>(last);
  };
  for (int j = 0; j < n; ++j) {
    if (p.travel[0][j + 1] <= p.due[j + 1]) best[at(std::size_t{1} << j, j)] = p.travel[0][j + 1];
  }
  for (std::size_t set = 1; set < sets; ++set) {
    for (int j = 0; j < n; ++j) {
      const double t = best[at(set, j)];
      if (t == inf) continue;
      for (int k = 0; k < n; ++k) {
        if ((set >> k) & 1U) continue;
        const double a = t + p.travel[j + 1][k + 1];
        double& next = best[at(set | (std::size_t{1} << k), k)];
        if (a <= p.due[k + 1] && a < next) next = a;
      }
    }
  }
  double optimum = inf;
  for (int j = 0; j < n; ++j)
    optimum = std::min(optimum, best[at(sets - 1, j)]);
  return optimum == inf ? -1.0 : optimum;
}

double gap_pct(const Outcome& o) {
  return o.reference > 0 ? 100.0 * (o.travel - o.reference) / o.reference : 0.0;
}

int print_one(const std::string& path, const uav::ScheduleProblem& p, const Solved& s) {
  const uav::ScheduleResult& r = s.result;
  std::printf("instance   %s (%d customers)\n", path.c_str(), p.n);
  std::printf("tour       0");
  for (const auto k : r.order)
    std::printf(" %d", k);
  std::printf(p.closed ? " 0\n" : "\n");
  std::printf("travel     %.3f\n", r.cost.travel_s);
  std::printf("feasible   %s (total lateness %.3f)\n", r.cost.feasible ? "yes" : "no",
              r.cost.lateness_s);
  std::printf("optimal    %s\n", r.exact ? "proven" : "not proven (heuristic)");
  std::printf("bound      travel >= %.3f, lateness >= %.3f\n", r.bound.travel_s,
              r.bound.lateness_s);
  std::printf("work       %llu\n", static_cast<unsigned long long>(s.work));
  std::printf("time       %.3f ms\n", s.ms);
  return 0;
}

}  // namespace

int run_scheduler_bench(const SchedulerBenchOptions& o) {
  uav::SchedulerConfig cfg;
  if (o.exact_max >= 0) cfg.exact_max_stops = o.exact_max;
  if (o.work > 0) cfg.work_budget = o.work;
  if (o.seed > 0) cfg.seed = o.seed;
  std::error_code ec;
  std::vector<std::string> files;
  const bool dir = fs::is_directory(o.instance, ec);
  if (dir) {
    for (const auto& e : fs::directory_iterator(o.instance, ec)) {
      if (e.is_regular_file() && e.path().extension() == ".txt" &&
          e.path().filename() != "README.txt")
        files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) {
      std::fprintf(stderr, "colag_bench scheduler: no *.txt instance in %s\n", o.instance.c_str());
      return 2;
    }
  } else {
    files.push_back(o.instance);
  }
  const std::string csv =
      !o.best_known.empty()
          ? o.best_known
          : ((dir ? fs::path(o.instance) : fs::path(o.instance).parent_path()) / "best_known.csv")
                .string();
  if (!o.best_known.empty() && !fs::is_regular_file(o.best_known, ec)) {
    std::fprintf(stderr, "colag_bench scheduler: %s: not a file\n", o.best_known.c_str());
    return 2;
  }
  // Closed: the published values beside the instances; any variant: the file given.
  const auto best_known = o.variant == "closed" || !o.best_known.empty()
                              ? read_best_known(csv)
                              : std::map<std::string, double>{};
  std::vector<Outcome> outcomes;
  // The references found, in best_known.csv's layout, for --best-known next time.
  std::ofstream reference_out;
  if (!o.reference_out.empty()) {
    reference_out.open(o.reference_out);
    if (!reference_out) {
      std::fprintf(stderr, "colag_bench scheduler: cannot write %s\n", o.reference_out.c_str());
      return 2;
    }
    reference_out << std::fixed << std::setprecision(0)
                  << "Benchmark Set,Instance Name,Best Known Solution\n";
  }
  auto problem = std::make_unique<uav::ScheduleProblem>();
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::string error;
    if (!read_tsptw(files[i], *problem, error)) {
      std::fprintf(stderr, "colag_bench scheduler: %s\n", error.c_str());
      return 2;
    }
    if (dir && problem->n > o.max_stops) continue;
    apply_variant(o.variant, *problem);
    const Solved s = solve(*problem, cfg, std::max(1, o.steps));
    if (!dir) return print_one(files[i], *problem, s);
    Outcome out;
    out.name = fs::path(files[i]).filename().string();
    out.n = problem->n;
    out.travel = s.result.cost.travel_s;
    out.feasible = s.result.cost.feasible;
    out.exact = s.result.exact;
    out.ms = s.ms;
    out.work = s.work;
    if (o.exact_reference && o.variant == "deadline" && problem->n <= kExactDeadlineStops) {
      out.reference = exact_deadline_optimum(*problem);
      out.reference_exact = true;
    } else if (const auto it = best_known.find(out.name); it != best_known.end()) {
      out.reference = it->second;
    } else if (o.reference_runs > 0) {
      // The best of several long runs (each 100 warm steps, seeded differently): a reference,
      // not an optimum.
      for (int run = 0; run < o.reference_runs; ++run) {
        uav::SchedulerConfig rc = cfg;
        rc.seed = cfg.seed + 1000 + static_cast<std::uint64_t>(run);
        const Solved ref = solve(*problem, rc, 100);
        if (ref.result.cost.feasible &&
            (out.reference < 0 || ref.result.cost.travel_s < out.reference))
          out.reference = ref.result.cost.travel_s;
      }
      if (out.feasible && out.reference > out.travel) out.reference = out.travel;
    }
    outcomes.push_back(out);
    if (reference_out.is_open() && out.reference > 0)
      reference_out << "Dumas," << out.name << ',' << out.reference << '\n';
    std::printf("%-18s n=%-3d travel %9.1f  ref %9.1f%s gap %6.2f %%  %-10s %8.2f ms  work %llu\n",
                out.name.c_str(), out.n, out.travel, out.reference, out.reference_exact ? "*" : " ",
                gap_pct(out), out.feasible ? "feasible" : "INFEASIBLE", out.ms,
                static_cast<unsigned long long>(out.work));
    std::fflush(stdout);
  }
  // Per size: feasible share, mean and max gap against the reference, time.
  std::map<int, std::vector<const Outcome*>> by_n;
  for (const Outcome& out : outcomes)
    by_n[out.n].push_back(&out);
  std::printf("\nvariant %s, %d step(s) of %llu work each; reference: %s\n", o.variant.c_str(),
              std::max(1, o.steps), static_cast<unsigned long long>(cfg.work_budget),
              o.exact_reference && o.variant == "deadline"
                  ? "optimum by dynamic programming where n <= 20 (*), else as below"
              : !o.best_known.empty() ? o.best_known.c_str()
              : o.variant == "closed" ? "published optimum (best_known.csv)"
                                      : "best of long runs (not proven optimal)");
  std::printf("%4s %9s %10s %9s %9s %10s %10s\n", "n", "instances", "feasible", "mean gap",
              "max gap", "mean ms", "max ms");
  bool ok = true;
  for (const auto& [n, list] : by_n) {
    int feasible = 0, with_ref = 0;
    double sum_gap = 0, max_gap = 0, sum_ms = 0, max_ms = 0;
    for (const Outcome* out : list) {
      feasible += out->feasible;
      sum_ms += out->ms;
      max_ms = std::max(max_ms, out->ms);
      if (out->reference > 0 && out->feasible) {
        ++with_ref;
        sum_gap += gap_pct(*out);
        max_gap = std::max(max_gap, gap_pct(*out));
      }
    }
    const double mean_gap = with_ref > 0 ? sum_gap / with_ref : 0.0;
    std::printf("%4d %9zu %6d/%-3zu %8.2f%% %8.2f%% %10.2f %10.2f\n", n, list.size(), feasible,
                list.size(), mean_gap, max_gap, sum_ms / static_cast<double>(list.size()), max_ms);
    if (o.max_mean_gap_pct >= 0 &&
        (mean_gap > o.max_mean_gap_pct || feasible < static_cast<int>(list.size())))
      ok = false;
  }
  return ok ? 0 : 1;
}

}  // namespace colag::programs
