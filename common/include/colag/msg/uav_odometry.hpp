#pragma once
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

// Whether the UAV's flight controller flies the mission (said on every odometry sample).
enum class UavFlight : std::uint8_t {
  kInControl = 0,  // flying the supervisor's setpoints
  kStarting = 1,   // arming, entering offboard, taking off: not supporting yet
  kLost = 2,       // the flight controller left the mission (`FlightFault` says why): UGVs stop
  kLanding = 3,    // the mission is over: landing, or landed
};
template <>
struct EnumRange<UavFlight> {
  static constexpr UavFlight kLast = UavFlight::kLanding;
};

inline const char* to_string(UavFlight f) {
  switch (f) {
    case UavFlight::kInControl:
      return "in_control";
    case UavFlight::kStarting:
      return "starting";
    case UavFlight::kLost:
      return "lost";
    case UavFlight::kLanding:
      return "landing";
  }
  return "unknown";
}

// Why the flight controller left the mission (with UavFlight::kLost), or why it has not
// taken it up yet (kStarting).
enum class FlightFault : std::uint8_t {
  kNone = 0,
  kSilent = 1,        // nothing heard from it within its timeout
  kFailsafe = 2,      // it reports a failsafe
  kLeftOffboard = 3,  // another mode was selected (a pilot, or its own failsafe action)
  kDisarmed = 4,      // disarmed in flight (a kill switch, a crash, a land detector)
  kRefused = 5,       // it refused the mode or arming command
  kNoAck = 6,         // it did not acknowledge the mode or arming command
  kWrongRelease = 7,  // its topics are not those of the configured release
};
template <>
struct EnumRange<FlightFault> {
  static constexpr FlightFault kLast = FlightFault::kWrongRelease;
};
inline const char* to_string(FlightFault f) {
  switch (f) {
    case FlightFault::kNone:
      return "none";
    case FlightFault::kSilent:
      return "flight controller silent";
    case FlightFault::kFailsafe:
      return "flight controller in failsafe";
    case FlightFault::kLeftOffboard:
      return "flight controller left offboard mode";
    case FlightFault::kDisarmed:
      return "flight controller disarmed";
    case FlightFault::kRefused:
      return "flight controller refused a command";
    case FlightFault::kNoAck:
      return "flight controller did not acknowledge a command";
    case FlightFault::kWrongRelease:
      return "flight controller speaks another release";
  }
  return "unknown";
}

// The UAV's SLAM odometry in the world frame (UAV -> UGVs, ~50-100 Hz), and whether it flies.
struct UavOdometry {
  TimePoint stamp;  // time of the pose
  RobotId uav_id = 0;
  double position_m[3] = {};                          // world frame
  double orientation_wxyz[4] = {1.0, 0.0, 0.0, 0.0};  // body -> world
  double velocity_mps[3] = {};                        // world frame
  double yaw_rate_radps = 0.0;
  UavFlight flight = UavFlight::kInControl;
  FlightFault fault = FlightFault::kNone;
  friend bool operator==(const UavOdometry&, const UavOdometry&) = default;
};
COLAG_MESSAGE_FIELDS(UavOdometry, stamp, uav_id, position_m, orientation_wxyz, velocity_mps,
                     yaw_rate_radps, flight, fault);

// High-rate and superseded quickly: best effort, with a short history so that a UGV can match
// relative-pose stamps; the UAV is expected at least every 200 ms.
template <>
inline constexpr TopicSpec<UavOdometry> kTopicSpec<UavOdometry> = {
    "colag_uav_odometry", &UavOdometry::uav_id, Reliability::kBestEffort, 16,
    std::chrono::milliseconds(200)};

}  // namespace colag::msg
