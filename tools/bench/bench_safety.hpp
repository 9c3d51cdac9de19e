#pragma once
// colag_bench safety: Monte-Carlo over maps x UGV counts x fault settings x seeds (every mission
// a colag_sim process with fault injection), reporting per fault setting the collisions, the
// minimum clearance, the reach rate and the waiting time; every mission also goes to CSV.
#include <string>
#include <vector>

namespace colag::programs {

struct SafetyOptions {
  int seeds = 2;
  int jobs = 2;
  std::string csv = "colag_safety.csv";
  double max_time_s = 400.0;
  bool quick = false;  // dense, 3 UGVs, two fault settings, one seed: a smoke run
  std::string sim;
  std::string world = "ideal";  // colag_sim --world: ideal, field or a YAML file
  // UGV counts to fly on every map; empty: 3, 5, 7 (pillars 3, 5, 8).
  std::vector<int> ugvs;
};

int run_safety(const SafetyOptions& options);

}  // namespace colag::programs
