#include "colag/hal/px4/px4_release.hpp"

#include <array>

#include "colag/hal/ros2/ros2_names.hpp"

namespace colag::hal::px4 {

namespace {

constexpr std::array<Px4Release, 2> kReleases = {Px4Release::kV115, Px4Release::kV116};

}  // namespace

Result<Px4Release> parse_px4_release(std::string_view text) {
  if (!text.empty() && (text.front() == 'v' || text.front() == 'V')) text.remove_prefix(1);
  if (text == "1.15") return Px4Release::kV115;
  if (text == "1.16") return Px4Release::kV116;
  return Status{Errc::kInvalidArgument, "unknown PX4 release (known: 1.15, 1.16)"};
}

const char* to_string(Px4Release r) {
  switch (r) {
    case Px4Release::kV115:
      return "1.15";
    case Px4Release::kV116:
      return "1.16";
  }
  return "unknown";
}

const char* px4_topic_name(Px4Release r, Px4Topic t) {
  switch (t) {
    case Px4Topic::kOffboardControlMode:
      return "fmu/in/offboard_control_mode";
    case Px4Topic::kTrajectorySetpoint:
      return "fmu/in/trajectory_setpoint";
    case Px4Topic::kVehicleCommand:
      return "fmu/in/vehicle_command";
    case Px4Topic::kVehicleCommandAck:
      return "fmu/out/vehicle_command_ack";
    case Px4Topic::kVehicleStatus:
      return r == Px4Release::kV115 ? "fmu/out/vehicle_status" : "fmu/out/vehicle_status_v1";
    case Px4Topic::kVehicleOdometry:
      return "fmu/out/vehicle_odometry";
  }
  return "";
}

std::string px4_dds_topic(Px4Release r, Px4Topic t, std::string_view ns) {
  return ros2::ros2_dds_topic(ns, px4_topic_name(r, t));
}

Result<Px4Release> release_of_status_topic(std::string_view dds_topic, std::string_view ns) {
  for (const Px4Release r : kReleases)
    if (dds_topic == px4_dds_topic(r, Px4Topic::kVehicleStatus, ns)) return r;
  return Status{Errc::kUnavailable, "not a PX4 vehicle status topic"};
}

}  // namespace colag::hal::px4
