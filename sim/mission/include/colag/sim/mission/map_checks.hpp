#pragma once
// Whether a loaded map fits the mission's layout (the paper's: starts at y = 16, goals at
// y = -16, lanes 2 m apart about x = 0). Refused: a map in the wrong units (wider than 1 km:
// millimetres?) or one the starts and goals lie outside (shifted to 0..35 m?): it would fly as
// an empty arena and report success. Warned: a start or goal inside an obstacle, no obstacle
// between the starts and the goals, a ground not at z = 0.
#include <string>
#include <vector>

#include "colag/sim/world/box_world.hpp"
#include "colag/sim/world/cloud_world.hpp"

namespace colag::mission {

struct MissionConfig;

// Against the mission's starts and goals (its placements, or the paper's layout).
bool check_map(const sim::BoxWorld& world, const sim::CloudWorldReport& report,
               const MissionConfig& cfg, std::vector<std::string>& warnings, std::string& error);

}  // namespace colag::mission
