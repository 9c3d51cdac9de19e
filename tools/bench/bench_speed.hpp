#pragma once
// colag_bench speed: the simulation's real-time factor, the speed target (dense map,
// 7 UGVs, seed 1: at least 50x). One mission is run several times, one colag_sim process at a
// time with every core; the median says more than any single run on a shared machine.
#include <string>

namespace colag::programs {

struct SpeedOptions {
  int runs = 5;
  std::string scenario = "dense";
  int ugvs = 7;
  int seed = 1;
  std::string world = "ideal";  // colag_sim --world: ideal, field or a YAML file
  double target = 50.0;         // real-time factor the median should reach
  double max_time_s = 400.0;
  std::string sim;  // path of colag_sim (default: next to colag_bench)
  // Another colag_sim (e.g. built from the previous commit): each run of ours follows one of
  // it, and the ratio of the median wall times is printed. On a shared machine whose speed
  // drifts by +-20 % within minutes, only such alternated runs compare two versions.
  std::string baseline;
};

// Prints every run's wall time and real-time factor, their median and best, and whether the
// median meets the target (with a baseline: its wall times too, and whether it flew the same
// mission). 0 if every run finished and flew the same mission, 1 otherwise (or 2: colag_sim not
// found).
int run_speed(const SpeedOptions& options);

}  // namespace colag::programs
