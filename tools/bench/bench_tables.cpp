#include "bench_tables.hpp"

#include "mission_pool.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

namespace colag::programs {

namespace {

using Config = MissionSpec;
Config spec(const std::string& scenario, int ugvs, const std::string& ablation, bool sp) {
  Config c;
  c.scenario = scenario;
  c.ugvs = ugvs;
  c.ablation = ablation;
  c.self_perception = sp;
  return c;
}
using Run = MissionRun;
// The dense map with n UGVs and k UAVs (Tables III and IV).
Config fleet(int ugvs, int uavs) {
  Config c = spec("dense", ugvs, "none", false);
  c.uavs = uavs;
  return c;
}

// The paper's numbers (reference/paper-results.md).
struct PaperRow {
  double reach, waiting, ugv_len, uav_len, sp_reach, sp_len;
};
const std::map<std::string, PaperRow> kTable1 = {
    {"sparse/1", {106.78, 0.00, 33.02, 36.35, 106.20, 32.92}},
    {"sparse/3", {106.13, 0.11, 32.96, 120.94, 106.59, 32.98}},
    {"sparse/5", {116.62, 3.87, 33.65, 214.07, 107.59, 33.32}},
    {"sparse/7", {129.12, 12.59, 33.59, 265.50, 106.92, 33.22}},
    {"dense/1", {112.30, 0.00, 34.95, 38.27, 111.04, 34.52}},
    {"dense/3", {112.38, 0.07, 34.73, 133.08, 110.69, 34.53}},
    {"dense/5", {119.54, 4.86, 34.68, 216.05, 110.50, 34.38}},
    {"dense/7", {143.18, 24.65, 34.98, 304.34, 111.88, 34.94}},
};
struct PaperAblation {
  const char* text;  // what the paper reports
};
const std::map<std::string, std::string> kTable2 = {
    {"none", "reach 119.54  wait 4.86  max 11.08  UGV 34.68  UAV 216.05"},
    {"no-rpe", "fails: pose drifts, UGVs collide"},
    {"no-uncertainty", "fails: UGVs collide"},
    {"no-scheduling", "reach 135.73  wait 18.10  max 27.85  UGV 34.85  UAV 239.71"},
    {"no-time-windows", "reach 132.43  wait 18.29  max 46.65  UGV 34.81  UAV 238.56"},
};

// Table IV's fleets, and the targets it sizes the UAVs for (issue 20's dense 7 field targets).
constexpr std::array<int, 4> kCapacityUgvs = {3, 7, 12, 16};
constexpr int kCapacityUavs = 4;
constexpr double kCapacityMaxRatio = 1.15;
constexpr double kCapacityMaxWait_s = 6.0;

struct Aggregate {
  Mean reach, waiting, max_waiting, ugv_len, uav_len, rt;
  int collisions = 0, runs = 0, all_reached = 0, failed = 0;
};

Aggregate aggregate(const std::vector<Run>& runs, const std::string& key) {
  Aggregate a;
  for (const Run& r : runs) {
    if (r.spec.key() != key) continue;
    ++a.runs;
    if (!r.ok) {
      ++a.failed;
      continue;
    }
    const auto& s = r.result["summary"];
    a.reach.add(s["reach_time_s"].is_null() ? NAN : s["reach_time_s"].get<double>());
    a.waiting.add(s["waiting_time_s"].get<double>());
    a.max_waiting.add(s["max_waiting_time_s"].get<double>());
    a.ugv_len.add(s["ugv_traj_length_m"].get<double>());
    a.uav_len.add(s["uav_traj_length_m"].get<double>());
    a.rt.add(r.result["realtime_factor"].get<double>());
    a.collisions += s["collisions"].get<int>();
    a.all_reached += s["all_reached"].get<bool>() ? 1 : 0;
  }
  return a;
}

// A table's number: two decimals, or "-" where nothing was measured.
std::string num(double v) {
  char b[16];
  std::snprintf(b, sizeof b, std::isfinite(v) ? "%.2f" : "-", v);
  return b;
}

// Table IV: the dense map with N UGVs and K UAVs, against the self-perception baseline; for each
// N, the fewest UAVs that keep reach and waiting within the targets.
void print_capacity(const std::vector<Run>& runs) {
  std::printf(
      "\nTable IV (beyond the paper): how many UGVs K UAVs serve. Dense map, N UGVs, K UAVs "
      "(averages over\nthe seeds, +- the 95 %% interval of the mean; ratio = reach / the "
      "self-perception baseline's)\n");
  std::printf("%-5s %-5s %9s %15s %7s %13s %7s %5s %8s\n", "UGVs", "UAVs", "UGVs/UAV", "reach",
              "ratio", "wait", "max", "coll", "reached");
  for (const int n : kCapacityUgvs) {
    const Aggregate sp = aggregate(runs, spec("dense", n, "none", true).key());
    int fewest = 0;
    bool measured = false;
    for (int k = 1; k <= kCapacityUavs; ++k) {
      const Aggregate a = aggregate(runs, fleet(n, k).key());
      if (a.runs == 0) continue;
      measured = true;
      const double ratio = a.reach.get() / sp.reach.get();
      // Every mission flown, every UGV there, none collided, both targets met on average.
      const bool within = a.failed == 0 && a.all_reached == a.runs && a.collisions == 0 &&
                          ratio <= kCapacityMaxRatio && a.waiting.get() <= kCapacityMaxWait_s;
      if (within && fewest == 0) fewest = k;
      std::printf("%-5d %-5d %9.1f %7s +-%5s %7s %6s +-%4s %7s %5d %4d/%-3d\n", n, k,
                  static_cast<double>(n) / k, num(a.reach.get()).c_str(),
                  num(a.reach.half95()).c_str(), num(ratio).c_str(), num(a.waiting.get()).c_str(),
                  num(a.waiting.half95()).c_str(), num(a.max_waiting.get()).c_str(), a.collisions,
                  a.all_reached, a.runs);
    }
    if (!measured) continue;
    if (fewest > 0) {
      std::printf("  %d UGVs: %d UAV%s keep%s reach within %.2fx and waiting within %.0f s\n", n,
                  fewest, fewest == 1 ? "" : "s", fewest == 1 ? "s" : "", kCapacityMaxRatio,
                  kCapacityMaxWait_s);
    } else {
      std::printf(
          "  %d UGVs: no count of 1-%d UAVs keeps reach within %.2fx and waiting within "
          "%.0f s\n",
          n, kCapacityUavs, kCapacityMaxRatio, kCapacityMaxWait_s);
    }
  }
}

}  // namespace

int run_tables(const TablesOptions& o) {
  std::vector<Config> configs;
  const bool t1 = o.tables == "1" || o.tables == "all", t2 = o.tables == "2" || o.tables == "all";
  const bool t3 = o.tables == "3" || o.tables == "all";
  const bool t4 = o.tables == "4" || o.tables == "all";
  if (o.quick) {
    configs = {spec("sparse", 1, "none", false), spec("sparse", 1, "none", true)};
  } else {
    if (t1) {
      for (const char* scen : {"sparse", "dense"}) {
        for (int n : {1, 3, 5, 7}) {
          configs.push_back(spec(scen, n, "none", false));
          configs.push_back(spec(scen, n, "none", true));
        }
      }
    }
    if (t2) {
      for (const char* a :
           {"none", "no-rpe", "no-uncertainty", "no-scheduling", "no-time-windows"}) {
        if (t1 && std::string(a) == "none") continue;  // already in Table I (dense/5)
        configs.push_back(spec("dense", 5, a, false));
      }
    }
    if (t3) {  // beyond the paper: several UAVs, scouting (dense 7: one UAV's hardest row)
      for (int k = 1; k <= 4; ++k) {
        for (const bool scouting : {false, true}) {
          Config c = fleet(7, k);
          c.scouting = scouting;
          if (!(t1 && k == 1 && !scouting)) configs.push_back(c);  // else in Table I
        }
      }
    }
    if (t4) {  // capacity: how many UGVs K UAVs serve (each configuration once, whatever table)
      const auto add = [&](const Config& c) {
        const bool known = std::any_of(configs.begin(), configs.end(),
                                       [&](const Config& d) { return d.key() == c.key(); });
        if (!known) configs.push_back(c);
      };
      for (const int n : kCapacityUgvs) {
        add(spec("dense", n, "none", true));
        for (int k = 1; k <= kCapacityUavs; ++k)
          add(fleet(n, k));
      }
    }
  }
  std::vector<Run> runs;
  for (const Config& c : configs) {
    for (int s = 1; s <= (o.quick ? 1 : o.seeds); ++s) {
      Run r;
      r.spec = c;
      r.spec.world = o.world;
      r.seed = s;
      runs.push_back(r);
    }
  }
  std::printf("colag_bench: %s world\n", o.world.c_str());
  std::printf("colag_bench: %zu missions (%d seed%s), %d at a time\n", runs.size(),
              o.quick ? 1 : o.seeds, o.seeds == 1 ? "" : "s", o.jobs);
  if (!run_missions(runs, sim_path(o.sim), o.jobs, o.max_time_s)) return 2;

  // CSV: one row per mission.
  std::ofstream csv(o.csv);
  csv << "scenario,ugvs,uavs,scouting,ablation,self_perception,seed,ok,all_reached,collisions,"
         "reach_time_s,"
         "waiting_time_s,"
         "max_waiting_time_s,ugv_traj_length_m,uav_traj_length_m,sim_time_s,realtime_factor\n";
  for (const Run& r : runs) {
    csv << r.spec.scenario << ',' << r.spec.ugvs << ',' << r.spec.uavs << ','
        << (r.spec.scouting ? "on" : "off") << ',' << r.spec.ablation << ','
        << r.spec.self_perception << ',' << r.seed << ',' << r.ok;
    if (r.ok) {
      const auto& s = r.result["summary"];
      csv << ',' << s["all_reached"].get<bool>() << ',' << s["collisions"].get<int>() << ','
          << (s["reach_time_s"].is_null() ? std::string("")
                                          : std::to_string(s["reach_time_s"].get<double>()))
          << ',' << s["waiting_time_s"].get<double>() << ','
          << s["max_waiting_time_s"].get<double>() << ',' << s["ugv_traj_length_m"].get<double>()
          << ',' << s["uav_traj_length_m"].get<double>() << ','
          << r.result["sim_time_s"].get<double>() << ','
          << r.result["realtime_factor"].get<double>();
    }
    csv << '\n';
  }

  if (t1 || o.quick) {
    std::printf(
        "\nTable I: averages per UGV over the seeds; paper in brackets. Reach = time to the goal "
        "(s),\n"
        "wait = stood still before the goal, any reason (s; the paper: stopped for support), "
        "length (m), S.P. = self-perception baseline, ratio = "
        "reach / S.P. reach.\n");
    std::printf("%-7s %4s %18s %16s %17s %18s %18s %17s %6s %5s %6s\n", "map", "UGVs",
                "reach [paper]", "wait [paper]", "UGV m [paper]", "UAV m [paper]",
                "S.P. reach [paper]", "S.P. m [paper]", "ratio", "coll", "reached");
    for (const char* scen : {"sparse", "dense"}) {
      for (int n : {1, 3, 5, 7}) {
        const Config c = spec(scen, n, "none", false), sp = spec(scen, n, "none", true);
        const Aggregate a = aggregate(runs, c.key()), b = aggregate(runs, sp.key());
        if (a.runs == 0) continue;
        const PaperRow& p = kTable1.at(std::string(scen) + "/" + std::to_string(n));
        std::printf(
            "%-7s %4d %8s [%7.2f] %6s [%6.2f] %7s [%6.2f] %8s [%6.2f] %8s [%7.2f] %7s [%6.2f] %6s "
            "%5d %3d/%-3d\n",
            scen, n, num(a.reach.get()).c_str(), p.reach, num(a.waiting.get()).c_str(), p.waiting,
            num(a.ugv_len.get()).c_str(), p.ugv_len, num(a.uav_len.get()).c_str(), p.uav_len,
            num(b.reach.get()).c_str(), p.sp_reach, num(b.ugv_len.get()).c_str(), p.sp_len,
            num(a.reach.get() / b.reach.get()).c_str(), a.collisions + b.collisions, a.all_reached,
            a.runs);
      }
    }
  }
  if (t2 && !o.quick) {
    std::printf(
        "\nTable II: dense map, 5 UGVs, each ablation (averages over the seeds, +- the 95 %% "
        "interval of the mean)\n");
    std::printf("%-16s %15s %13s %7s %7s %8s %5s %8s   %s\n", "method", "reach", "wait", "max",
                "UGV m", "UAV m", "coll", "reached", "paper");
    for (const char* ab :
         {"none", "no-rpe", "no-uncertainty", "no-scheduling", "no-time-windows"}) {
      const Aggregate a = aggregate(runs, spec("dense", 5, ab, false).key());
      if (a.runs == 0) continue;
      std::printf("%-16s %7s +-%5s %6s +-%4s %7s %7s %8s %5d %4d/%-3d   %s\n", ab,
                  num(a.reach.get()).c_str(), num(a.reach.half95()).c_str(),
                  num(a.waiting.get()).c_str(), num(a.waiting.half95()).c_str(),
                  num(a.max_waiting.get()).c_str(), num(a.ugv_len.get()).c_str(),
                  num(a.uav_len.get()).c_str(), a.collisions, a.all_reached, a.runs,
                  kTable2.at(ab).c_str());
    }
  }
  if (t3 && !o.quick) {
    std::printf(
        "\nTable III (beyond the paper): dense map, 7 UGVs, K UAVs sharing the support, scouting "
        "off / on\n(averages over the seeds, +- the 95 %% interval of the mean; UAV m: all UAVs' "
        "flying, summed)\n");
    std::printf("%-5s %-9s %15s %13s %7s %7s %8s %5s %8s\n", "UAVs", "scouting", "reach", "wait",
                "max", "UGV m", "UAV m", "coll", "reached");
    for (int k = 1; k <= 4; ++k) {
      for (const bool scouting : {false, true}) {
        Config c = fleet(7, k);
        c.scouting = scouting;
        const Aggregate a = aggregate(runs, c.key());
        if (a.runs == 0) continue;
        std::printf("%-5d %-9s %7s +-%5s %6s +-%4s %7s %7s %8s %5d %4d/%-3d\n", k,
                    scouting ? "on" : "off", num(a.reach.get()).c_str(),
                    num(a.reach.half95()).c_str(), num(a.waiting.get()).c_str(),
                    num(a.waiting.half95()).c_str(), num(a.max_waiting.get()).c_str(),
                    num(a.ugv_len.get()).c_str(), num(a.uav_len.get()).c_str(), a.collisions,
                    a.all_reached, a.runs);
      }
    }
  }
  if (t4 && !o.quick) print_capacity(runs);
  Mean rt;
  for (const Run& r : runs) {
    if (r.ok && !r.spec.self_perception) rt.add(r.result["realtime_factor"].get<double>());
  }
  std::printf("\nmean real-time factor of the ColAG runs: %.0fx;  per-mission CSV: %s\n", rt.get(),
              o.csv.c_str());
  int failed = 0;
  for (const Run& r : runs)
    failed += r.ok ? 0 : 1;
  if (failed > 0) std::printf("%d mission%s failed to run\n", failed, failed == 1 ? "" : "s");
  return failed > 0 ? 1 : 0;
}

}  // namespace colag::programs
