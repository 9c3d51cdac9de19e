#pragma once
// colag_world's end of the sim link: moves each UGV's CAN frames between the simulated motor
// controller and the UGV's process, publishes the UAV's state, LiDAR scans and relative-pose
// frames, and hands the UAV's flight setpoints to its simulated body.
#include <vector>

#include "colag/hal/sim/sim_link.hpp"
#include "colag/sim/world/sim_world.hpp"

namespace colag::sim {

struct BridgeCounters {
  std::uint64_t frames_to_robots = 0;
  std::uint64_t frames_from_robots = 0;
  std::uint64_t frames_for_unknown_robots = 0;
  std::uint64_t setpoints = 0;
  std::uint64_t scans = 0;
  std::uint64_t scan_bytes = 0;
  std::uint64_t rpe_frames = 0;
};

class WorldBridge {
 public:
  // `uav_camera_only`: the UAV flies on its flight stack's wire formats (Px4StackBridge): only
  // its camera (our own device) stays on the sim link.
  WorldBridge(hal::sim::SimLink& link, SimWorld& world, bool with_uav,
              bool uav_camera_only = false);
  // Call at least every control period (10 ms): frames both ways, then the UAV's data.
  void step();
  const BridgeCounters& counters() const { return counters_; }

 private:
  void fly_uav();

  hal::sim::SimLink& link_;
  SimWorld& world_;
  bool with_uav_;
  bool uav_camera_only_;
  std::vector<std::int16_t> xyz_mm_;  // scan staging, sized once
  BridgeCounters counters_;
};

}  // namespace colag::sim
