#pragma once
// The UAV's schedule table: every loop of the UAV firmware with its period, budget and offset,
// declared once. The board program (uav_fw, on a UAV and in SITL) and the lock-step simulation
// (colag_sim) both build their executor table from it, and the loops take their periods from it.
#include "colag/platform/task.hpp"

namespace colag::uav {

struct UavSchedule {
  // Transport::poll, first in the table (on a board; in the lock-step simulation the robots share
  // one network, polled by the mission at its own rate).
  platform::LoopTiming transport{std::chrono::milliseconds(10), std::chrono::milliseconds(2)};
  // 50 Hz: odometry -> UavOdometry, camera -> RelativePose, flight setpoints.
  platform::LoopTiming control{std::chrono::milliseconds(20), std::chrono::milliseconds(5)};
  // 10 Hz (the LiDAR's rate): scan -> 3-D map; the flight layer once a second.
  platform::LoopTiming mapping{std::chrono::milliseconds(100), std::chrono::milliseconds(50)};
  // 20 Hz: a map patch to each UGV whose own 5 Hz slot is due.
  platform::LoopTiming sharing{std::chrono::milliseconds(50), std::chrono::milliseconds(10)};
  // 10 Hz: requests and statuses -> schedule -> flight target, SupportPlan.
  platform::LoopTiming scheduling{std::chrono::milliseconds(100), std::chrono::milliseconds(20)};
  // 10 Hz, on a board with ROS 2 telemetry on (`ros2.enabled`): the task's state copied for the
  // telemetry's own thread, its 2-D map view a slice of rows per step.
  platform::LoopTiming telemetry{std::chrono::milliseconds(100), std::chrono::milliseconds(3)};
};

}  // namespace colag::uav
