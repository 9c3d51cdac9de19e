#pragma once
// colag_sim's and colag_world's --scenario-file and --world: the file's mission, then what the
// command line gave explicitly, then the world profile by name unless the file gave it.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "colag/sim/mission/mission_config.hpp"
#include "colag/sim/mission/scenario_file.hpp"
#include "colag/sim/mission/world_file.hpp"

namespace colag::sim {

// 0, or 2 (a usage or input error) after saying why on stderr as `program`.
inline int apply_scenario_options(const CLI::App& app, const char* program,
                                  const std::string& scenario_file, const std::string& world_name,
                                  mission::MissionConfig& cfg) {
  const auto given = [&app](const char* name) {
    const CLI::Option* o = app.get_option_no_throw(name);
    return o != nullptr && o->count() > 0;
  };
  if (!scenario_file.empty()) {
    const mission::MissionConfig cli = cfg;
    if (std::string error; !mission::load_scenario_file(scenario_file, cfg, error)) {
      std::fprintf(stderr, "%s: --scenario-file: %s\n", program, error.c_str());
      return 2;
    }
    if (given("--seed")) cfg.seed = cli.seed;
    if (given("--max-time")) cfg.max_time_s = cli.max_time_s;
    if (given("--latency-ms")) cfg.faults.latency_ms = cli.faults.latency_ms;
    if (given("--jitter-ms")) cfg.faults.jitter_ms = cli.faults.jitter_ms;
  }
  if (scenario_file.empty() || given("--world")) {
    if (std::string error; !mission::world_from_name(world_name, cfg.world, error)) {
      std::fprintf(stderr, "%s: --world: %s\n", program, error.c_str());
      return 2;
    }
  }
  return 0;
}

}  // namespace colag::sim
