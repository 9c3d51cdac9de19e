#pragma once
// The UGV's schedule table: every loop of the UGV firmware with its period, budget and offset,
// declared once. All three ways of running a UGV build their executor table from it: the board
// program (ugv_fw on a robot), SITL (the same program on colag_world's simulated CAN bus) and
// the lock-step simulation (colag_sim, each UGV in a lane of its own). A board's configuration
// may change the rates (ugv.yaml `rates:`); a budget keeps its share of the period.
#include "colag/platform/task.hpp"

namespace colag::ugv {

struct UgvSchedule {
  // Transport::poll, first in the table at every control tick, so both loops see one inbox. On
  // a board only: in the lock-step simulation the robots share one network, polled by the
  // mission at its own rate.
  platform::LoopTiming transport{std::chrono::milliseconds(20), std::chrono::milliseconds(5)};
  // 50 Hz: encoders -> EKF predict, relative poses -> EKF update, path tracking -> Drive.
  platform::LoopTiming control{std::chrono::milliseconds(20), std::chrono::milliseconds(5)};
  // 10 Hz: map patches, other UGVs, (re)planning, collision prediction, support, status. Released
  // with the control loop and run after it: a long plan delays no control step unless it takes
  // a whole control period.
  platform::LoopTiming planning{std::chrono::milliseconds(100), std::chrono::milliseconds(50)};
  // 10 Hz, on a board with ROS 2 telemetry on (`ros2.enabled`): the task's state handed to the
  // telemetry's own thread (a copy; DDS runs there), and goals from ROS 2 handed to the task.
  platform::LoopTiming telemetry{std::chrono::milliseconds(100), std::chrono::milliseconds(2)};
};

}  // namespace colag::ugv
