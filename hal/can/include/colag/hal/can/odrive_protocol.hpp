#pragma once
// ODrive's "CAN Simple" protocol (firmware 0.5.x), wheel level: a pure codec. Each axis is a
// node (id 0..63); the 11-bit CAN id is node << 5 | command; payloads are little endian.
// Facts from ODrive's published protocol table. The driver is odrive_base.hpp; the emulator of an
// ODrive (the simulated world, HIL) uses the axis side below.
#include <cstdint>

#include "colag/hal/can_bus.hpp"

namespace colag::hal::can::odrive {

inline constexpr std::uint8_t kMaxNodeId = 0x3F;

enum class Command : std::uint8_t {
  kHeartbeat = 0x01,          // axis -> host, cyclic (100 ms by default)
  kEstop = 0x02,              // host -> axis
  kSetAxisState = 0x07,       // host -> axis: u32 requested state
  kEncoderEstimates = 0x09,   // axis -> host, cyclic (10 ms): f32 pos (turns), f32 vel (turns/s)
  kSetControllerMode = 0x0B,  // host -> axis: i32 control mode, i32 input mode
  kSetInputVel = 0x0D,        // host -> axis: f32 vel (turns/s), f32 torque feed-forward (N m)
  kClearErrors = 0x18,        // host -> axis
};

// Axis states (the ones the firmware uses).
inline constexpr std::uint32_t kAxisStateIdle = 1;
inline constexpr std::uint32_t kAxisStateClosedLoop = 8;
// Axis error bits (0.5.x) the emulator raises; the driver reports any bit.
inline constexpr std::uint32_t kAxisErrorMotorFailed = 0x40;
inline constexpr std::uint32_t kAxisErrorWatchdogExpired = 0x800;
inline constexpr std::uint32_t kAxisErrorEstopRequested = 0x4000;
// Controller modes.
inline constexpr std::int32_t kControlModeVelocity = 2;
inline constexpr std::int32_t kInputModePassthrough = 1;
inline constexpr std::int32_t kInputModeVelRamp = 2;

struct Heartbeat {
  std::uint32_t axis_error = 0;
  std::uint8_t axis_state = 0;
  bool motor_error = false, encoder_error = false, controller_error = false;
};
struct EncoderEstimates {
  float pos_turns = 0.0F;
  float vel_turns_per_s = 0.0F;
};

constexpr std::uint32_t can_id(std::uint8_t node, Command c) {
  return (static_cast<std::uint32_t>(node) << 5) | static_cast<std::uint32_t>(c);
}

CanFrame set_axis_state(std::uint8_t node, std::uint32_t state);
CanFrame set_controller_mode(std::uint8_t node, std::int32_t control_mode, std::int32_t input_mode);
CanFrame set_input_vel(std::uint8_t node, float vel_turns_per_s, float torque_ff_nm);
CanFrame estop(std::uint8_t node);
CanFrame clear_errors(std::uint8_t node);

enum class DecodeError : std::uint8_t { kNone, kOtherNode, kExtendedId, kNotFeedback, kWrongDlc };

// A frame from `node`: which feedback it is, or why it is not one of ours.
struct Feedback {
  Command command = Command::kHeartbeat;
  Heartbeat heartbeat;
  EncoderEstimates estimates;
};
DecodeError decode(const CanFrame& frame, std::uint8_t node, Feedback& out);

// The axis side (an ODrive, or its emulator): feedback out, commands in.
CanFrame heartbeat(std::uint8_t node, const Heartbeat& h);
CanFrame encoder_estimates(std::uint8_t node, const EncoderEstimates& e);
struct CommandFrame {
  Command command = Command::kEstop;
  std::uint32_t requested_state = 0;                  // kSetAxisState
  std::int32_t control_mode = 0, input_mode = 0;      // kSetControllerMode
  float vel_turns_per_s = 0.0F, torque_ff_nm = 0.0F;  // kSetInputVel
};
// kNotFeedback here means: not one of the commands above (a feedback frame, or unused).
DecodeError decode_command(const CanFrame& frame, std::uint8_t node, CommandFrame& out);

}  // namespace colag::hal::can::odrive
