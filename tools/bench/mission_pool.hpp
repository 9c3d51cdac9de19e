#pragma once
// Runs many missions as separate colag_sim processes, a few at a time, and reads back each one's
// JSON: what colag_bench's table and safety modes share.
#include <sys/types.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace colag::programs {

struct MissionSpec {
  std::string scenario = "dense";
  int ugvs = 1;
  std::string ablation = "none";
  bool self_perception = false;
  std::string faults = "none";          // a label for the fault setting
  std::vector<std::string> fault_args;  // colag_sim's fault options for it
  std::string world = "ideal";          // colag_sim --world
  int uavs = 1;                         // colag_sim --uavs
  bool scouting = false;                // colag_sim --scouting on
  std::string key() const;
};

struct MissionRun {
  MissionSpec spec;
  int seed = 0;
  std::string json_path;
  pid_t pid = 0;
  bool ok = false;  // it ran (whatever its outcome) and wrote its JSON
  nlohmann::json result;
};

// colag_sim next to the running program, unless `explicit_path` is given.
std::string sim_path(const std::string& explicit_path);

// Runs every mission (`jobs` at a time, each with an equal share of the cores), printing one
// progress line per finished mission. False if colag_sim could not be started at all.
bool run_missions(std::vector<MissionRun>& runs, const std::string& sim, int jobs,
                  double max_time_s);

struct Mean {
  double sum = 0;
  double sum_sq = 0;
  int n = 0;
  void add(double v);
  double get() const;
  // Half-width of the 95 % confidence interval of the mean (Student's t; NaN below 2 samples).
  double half95() const;
};

}  // namespace colag::programs
