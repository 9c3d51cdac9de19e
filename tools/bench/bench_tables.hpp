#pragma once
// colag_bench tables: the paper's Table I and Table II, measured; Table III (several UAVs,
// scouting) and Table IV (how many UGVs K UAVs serve), beyond the paper. Every run is one colag_sim
// process (the real firmware tasks, seeded), several at a time; the averages over the seeds
// are printed beside the paper's numbers and every run is written to CSV.
#include <string>

namespace colag::programs {

struct TablesOptions {
  int seeds = 5;
  int jobs = 2;                // processes at once
  std::string tables = "all";  // "1", "2", "3", "4" or "all"
  std::string csv = "colag_bench.csv";
  double max_time_s = 400.0;
  bool quick = false;           // one small configuration: a smoke run
  std::string sim;              // path of colag_sim (default: next to colag_bench)
  std::string world = "ideal";  // colag_sim --world: ideal, field or a YAML file
};

int run_tables(const TablesOptions& options);

}  // namespace colag::programs
