#pragma once
// AgileX's CAN protocol V2 (Scout, Scout Mini, Hunter, Tracer, Bunker), chassis level: a pure
// codec. 500 kbit/s, standard ids, 8-byte frames, multi-byte fields big endian. Facts from
// AgileX's published protocol (the user manuals' CAN tables and their SDK's headers).
#include <cstdint>

#include "colag/hal/can_bus.hpp"

namespace colag::hal::can::agilex {

// Host -> base.
inline constexpr std::uint32_t kMotionCommandId = 0x111;  // linear, angular (and steering) speed
inline constexpr std::uint32_t kControlModeId = 0x421;    // select CAN command mode
inline constexpr std::uint32_t kStateResetId = 0x441;     // clear the base's error state
// Base -> host.
inline constexpr std::uint32_t kSystemStateId = 0x211;
inline constexpr std::uint32_t kMotionStateId = 0x221;
inline constexpr std::uint32_t kOdometryId = 0x311;

inline constexpr std::uint8_t kVehicleNormal = 0x00;
inline constexpr std::uint8_t kVehicleEstop = 0x01;
inline constexpr std::uint8_t kVehicleException = 0x02;
inline constexpr std::uint8_t kControlModeRc = 0x00;  // standby / remote control
inline constexpr std::uint8_t kControlModeCan = 0x01;
// System state fault bits.
inline constexpr std::uint8_t kFaultBatteryLow = 0x01;      // too low to drive
inline constexpr std::uint8_t kFaultBatteryWarning = 0x02;  // low: a warning only
inline constexpr std::uint8_t kFaultRcSignalLost = 0x04;

struct MotionCommand {
  std::int16_t linear_mmps = 0;     // mm/s
  std::int16_t angular_mradps = 0;  // 0.001 rad/s, counter-clockwise positive
};
using MotionState = MotionCommand;  // the measured motion, same layout
struct SystemState {
  std::uint8_t vehicle_state = kVehicleNormal;
  std::uint8_t control_mode = kControlModeRc;
  std::uint16_t battery_dv = 0;  // 0.1 V
  std::uint8_t fault = 0;
  std::uint8_t count = 0;
};
struct Odometry {
  std::int32_t left_mm = 0;  // each side's travel since power-up
  std::int32_t right_mm = 0;
};

CanFrame encode(const MotionCommand& m);
CanFrame encode_motion_state(const MotionState& m);
CanFrame encode(const SystemState& m);
CanFrame encode(const Odometry& m);
CanFrame control_mode(std::uint8_t mode);
CanFrame state_reset();

enum class DecodeError : std::uint8_t { kNone, kUnknownId, kExtendedId, kWrongDlc };

struct Decoded {
  std::uint32_t id = 0;  // which of the messages above
  MotionCommand motion;  // kMotionCommandId, kMotionStateId
  SystemState system;
  Odometry odometry;
  std::uint8_t mode = 0;  // kControlModeId
};
DecodeError decode(const CanFrame& frame, Decoded& out);

}  // namespace colag::hal::can::agilex
