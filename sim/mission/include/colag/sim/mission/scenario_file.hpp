#pragma once
// A mission from a YAML scenario file: the map (a generator or a PCD file, in metres), the seed,
// the world profile, each UGV's start pose and goal, the UAV's start, network faults and the time
// limit (config/scenarios/README.md documents every key). What the file does not set keeps the
// value `cfg` had (the command line's). Unknown keys, wrong types, values out of range, a start
// or goal outside what the maps cover, two UGVs starting on top of each other: refused with
// "FILE: key.path: problem".
#include <string>

#include "colag/sim/mission/mission_config.hpp"

namespace colag::mission {

bool load_scenario_file(const std::string& file, MissionConfig& cfg, std::string& error);

}  // namespace colag::mission
