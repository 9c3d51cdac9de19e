#pragma once
// Draws a simulated mission, seen from above: obstacles, what stayed unknown to the UAV, each
// UGV's true path (solid) and estimate (dots), its 3-sigma ellipses every 5 s, the support
// points it asked for, the UAV's route, and every collision in red; axes in metres. The view
// fits the arena and every path, whatever the map's size or shape; the caption is below it.
#include <string>

#include "colag/sim/mission/mission.hpp"

namespace colag::programs {

bool draw_mission(const mission::MissionTrace& trace, const mission::MissionOutcome& outcome,
                  const std::string& path, std::string& error);

}  // namespace colag::programs
