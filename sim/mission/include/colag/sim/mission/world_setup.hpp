#pragma once
// From a mission's configuration (its world profile, seed and faults) to the simulated world's
// and the robots' settings: shared by the lock-step simulator (colag_sim) and the SITL world
// (colag_world), so both simulate the same robots in the same world.
#include <vector>

#include "colag/sim/mission/mission_config.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "colag/uav/camera_altitude.hpp"
#include "colag/uav/no_return_beams.hpp"

namespace colag::mission {

// The world's sensors and bodies, from the profile (the UGVs' wheels: draw_wheels).
sim::SimWorldConfig sim_world_config(const MissionConfig& cfg);
// Each UGV's wheels, drawn from the profile on the mission's seed (a stream of their own).
std::vector<sim::WheelErrors> draw_wheels(const MissionConfig& cfg);
// What the UAV's firmware is told of its sensors (the UAV's config file on a board).
uav::LidarBeamPattern beam_pattern_of(const sim::LidarPattern& p);
uav::CameraView camera_view_of(const sim::CameraConfig& c);

}  // namespace colag::mission
