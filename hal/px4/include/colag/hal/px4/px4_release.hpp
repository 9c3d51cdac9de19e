#pragma once
// The PX4 releases the flight-controller driver speaks, and each one's topic names. A release's
// messages differ in layout and, from v1.16, in name (a versioned message's topic ends in
// `_v<N>`): the configuration names the release, and the driver refuses to guess.
#include <cstdint>
#include <string>
#include <string_view>

#include "colag/common/status.hpp"

namespace colag::hal::px4 {

enum class Px4Release : std::uint8_t { kV115, kV116 };

// "1.15" / "v1.15", "1.16" / "v1.16"; anything else is refused (the message lists the known ones).
Result<Px4Release> parse_px4_release(std::string_view text);
const char* to_string(Px4Release r);
inline constexpr const char* kKnownPx4Releases = "1.15, 1.16";

enum class Px4Topic : std::uint8_t {
  kOffboardControlMode,  // in
  kTrajectorySetpoint,   // in
  kVehicleCommand,       // in
  kVehicleCommandAck,    // out
  kVehicleStatus,        // out (versioned from v1.16)
  kVehicleOdometry,      // out
};
inline constexpr std::size_t kPx4TopicCount = 6;

// The topic's PX4 name, without namespace or prefix: "fmu/out/vehicle_status_v1".
const char* px4_topic_name(Px4Release r, Px4Topic t);
// The DDS topic name: "rt/" + namespace + "/" + name (no namespace: "rt/fmu/...").
std::string px4_dds_topic(Px4Release r, Px4Topic t, std::string_view ns);
// The release whose VehicleStatus topic is `dds_topic` in namespace `ns`, if any (for telling
// a user which release is on the bus when it is not the configured one).
Result<Px4Release> release_of_status_topic(std::string_view dds_topic, std::string_view ns);

}  // namespace colag::hal::px4
