#pragma once
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

enum class UgvMode : std::uint8_t {
  kWaitingForInit = 0,  // no relative pose seen yet: the estimator is not initialised
  kDriving = 1,
  kWaitingForSupport = 2,  // stopped: predicted collision closer than the stop threshold
  kArrived = 3,
  kNoPath = 4,   // the planner finds no route to the goal in the current map
  kFault = 5,    // sensor or actuator failure: motors commanded to zero
  kBlocked = 6,  // stood still too long for `blocked_reason`: stopped asking for support, retries
  kWaitingForRobot = 7,  // stopped: another UGV predicted closer than the robot stop time
  kUavUnavailable = 8,   // stopped: the UAV says its flight controller does not fly the mission
  kPaused = 9,           // stopped by its operator (a `pause` command) until `resume`
  kAborted = 10,  // its mission cancelled by its operator: stopped until a new goal or `return`
};
template <>
struct EnumRange<UgvMode> {
  static constexpr UgvMode kLast = UgvMode::kAborted;
};

// Its name in telemetry (ROS 2 status, logs).
inline const char* to_string(UgvMode m) {
  switch (m) {
    case UgvMode::kWaitingForInit:
      return "waiting_for_init";
    case UgvMode::kDriving:
      return "driving";
    case UgvMode::kWaitingForSupport:
      return "waiting_for_support";
    case UgvMode::kArrived:
      return "arrived";
    case UgvMode::kNoPath:
      return "no_path";
    case UgvMode::kFault:
      return "fault";
    case UgvMode::kBlocked:
      return "blocked";
    case UgvMode::kWaitingForRobot:
      return "waiting_for_robot";
    case UgvMode::kUavUnavailable:
      return "uav_unavailable";
    case UgvMode::kPaused:
      return "paused";
    case UgvMode::kAborted:
      return "aborted";
  }
  return "unknown";
}

// Why a UGV stands still (what it reports with kBlocked).
enum class BlockedReason : std::uint8_t {
  kNone = 0,
  kNotLocalised = 1,   // no relative pose has initialised its estimator
  kNoPath = 2,         // no route to its goal in its map
  kNotCleared = 3,     // a collision stays predicted: the UAV's support did not clear the way
  kRobotInTheWay = 4,  // another UGV stays in its way
};
template <>
struct EnumRange<BlockedReason> {
  static constexpr BlockedReason kLast = BlockedReason::kRobotInTheWay;
};
inline const char* to_string(BlockedReason r) {
  switch (r) {
    case BlockedReason::kNone:
      return "not blocked";
    case BlockedReason::kNotLocalised:
      return "not localised: no relative pose";
    case BlockedReason::kNoPath:
      return "no path to its goal";
    case BlockedReason::kNotCleared:
      return "support did not clear the way";
    case BlockedReason::kRobotInTheWay:
      return "another UGV in the way";
  }
  return "unknown reason";
}

// Why a UGV is in kFault: its wheel odometry or its base (motor controllers, chassis).
enum class BaseFault : std::uint8_t {
  kNone = 0,
  kOdometrySilent = 1,  // no wheel odometry within its timeout
  kBaseSilent = 2,      // the base's heartbeat / state stopped
  kNotReady = 3,        // the base does not take commands (not in closed loop / CAN mode)
  kMotorError = 4,      // the base reports an error (`base_error` holds its code)
  kEstop = 5,           // the base's emergency stop is pressed
  kBusOff = 6,          // the CAN controller went bus-off
  kLowBattery = 7,      // the base reports its battery too low to drive
};
template <>
struct EnumRange<BaseFault> {
  static constexpr BaseFault kLast = BaseFault::kLowBattery;
};
inline const char* to_string(BaseFault f) {
  switch (f) {
    case BaseFault::kNone:
      return "none";
    case BaseFault::kOdometrySilent:
      return "wheel odometry silent";
    case BaseFault::kBaseSilent:
      return "base silent";
    case BaseFault::kNotReady:
      return "base not taking commands";
    case BaseFault::kMotorError:
      return "base reports an error";
    case BaseFault::kEstop:
      return "emergency stop";
    case BaseFault::kBusOff:
      return "CAN bus-off";
    case BaseFault::kLowBattery:
      return "battery too low";
  }
  return "unknown fault";
}

// A UGV's estimated state (UGV -> UAV and the other UGVs, ~10 Hz).
struct UgvStatus {
  TimePoint stamp;
  RobotId ugv_id = 0;
  UgvMode mode = UgvMode::kWaitingForInit;
  double position_m[2] = {};  // EKF estimate, world frame
  double yaw_rad = 0.0;
  double covariance[9] = {};  // (x, y, yaw), 3x3 row-major: m^2, m*rad, rad^2
  double velocity_mps = 0.0;  // commanded forward speed
  double yaw_rate_radps = 0.0;
  double goal_m[2] = {};
  double waiting_time_s = 0.0;  // accumulated time standing still before arrival (any reason)
  BlockedReason blocked_reason = BlockedReason::kNone;  // with kBlocked: why
  double clock_error_s = -1.0;        // how far its fleet time may be off; < 0: not synchronised
  std::uint32_t rejected_inputs = 0;  // health: malformed or out-of-gate inputs so far
  std::uint32_t overruns = 0;         // health: task steps over their budget so far
  std::uint8_t degradation = 0;       // health: 0 = full work; > 0 = shedding work (overruns)
  BaseFault base_fault = BaseFault::kNone;  // with kFault: why
  std::uint32_t base_error = 0;             // the base's own error code (with kMotorError)
  // Where its planned path first comes near an unknown cell (beyond where it is now, within its
  // scout range), and in how many seconds of driving it gets there; < 0: none. The UAV maps
  // there when it has nothing requested (scouting), before the UGV has to stop and ask.
  double scout_point_m[2] = {};
  double scout_in_s = -1.0;
  friend bool operator==(const UgvStatus&, const UgvStatus&) = default;
};
COLAG_MESSAGE_FIELDS(UgvStatus, stamp, ugv_id, mode, position_m, yaw_rad, covariance, velocity_mps,
                     yaw_rate_radps, goal_m, waiting_time_s, blocked_reason, clock_error_s,
                     rejected_inputs, overruns, degradation, base_fault, base_error, scout_point_m,
                     scout_in_s);

// Superseded by the next one 100 ms later: best effort; a UGV is expected every 500 ms.
template <>
inline constexpr TopicSpec<UgvStatus> kTopicSpec<UgvStatus> = {"colag_ugv_status",
                                                               &UgvStatus::ugv_id,
                                                               Reliability::kBestEffort,
                                                               4,
                                                               std::chrono::milliseconds(500),
                                                               Delivery::kPerUgv};

}  // namespace colag::msg
