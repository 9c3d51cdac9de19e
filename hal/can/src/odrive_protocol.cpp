#include "colag/hal/can/odrive_protocol.hpp"

#include <bit>

namespace colag::hal::can::odrive {

namespace {

void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint32_t get_u32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}

CanFrame frame(std::uint8_t node, Command c, std::uint8_t dlc) {
  CanFrame f;
  f.id = can_id(node & kMaxNodeId, c);
  f.dlc = dlc;
  return f;
}

}  // namespace

CanFrame set_axis_state(std::uint8_t node, std::uint32_t state) {
  CanFrame f = frame(node, Command::kSetAxisState, 4);
  put_u32(f.data, state);
  return f;
}

CanFrame set_controller_mode(std::uint8_t node, std::int32_t control_mode,
                             std::int32_t input_mode) {
  CanFrame f = frame(node, Command::kSetControllerMode, 8);
  put_u32(f.data, static_cast<std::uint32_t>(control_mode));
  put_u32(f.data + 4, static_cast<std::uint32_t>(input_mode));
  return f;
}

CanFrame set_input_vel(std::uint8_t node, float vel_turns_per_s, float torque_ff_nm) {
  CanFrame f = frame(node, Command::kSetInputVel, 8);
  put_u32(f.data, std::bit_cast<std::uint32_t>(vel_turns_per_s));
  put_u32(f.data + 4, std::bit_cast<std::uint32_t>(torque_ff_nm));
  return f;
}

CanFrame estop(std::uint8_t node) {
  return frame(node, Command::kEstop, 0);
}

CanFrame clear_errors(std::uint8_t node) {
  return frame(node, Command::kClearErrors, 0);
}

DecodeError decode(const CanFrame& f, std::uint8_t node, Feedback& out) {
  if (f.extended) return DecodeError::kExtendedId;
  if ((f.id >> 5) != (node & kMaxNodeId)) return DecodeError::kOtherNode;
  const auto c = static_cast<Command>(f.id & 0x1F);
  switch (c) {
    case Command::kHeartbeat:
      // 7 bytes on older firmware (no trajectory flag), 8 on 0.5.x.
      if (f.dlc < 7) return DecodeError::kWrongDlc;
      out.command = c;
      out.heartbeat.axis_error = get_u32(f.data);
      out.heartbeat.axis_state = f.data[4];
      out.heartbeat.motor_error = (f.data[5] & 1U) != 0;
      out.heartbeat.encoder_error = (f.data[6] & 1U) != 0;
      out.heartbeat.controller_error = f.dlc == 8 && (f.data[7] & 1U) != 0;
      return DecodeError::kNone;
    case Command::kEncoderEstimates: {
      if (f.dlc != 8) return DecodeError::kWrongDlc;
      out.command = c;
      out.estimates.pos_turns = std::bit_cast<float>(get_u32(f.data));
      out.estimates.vel_turns_per_s = std::bit_cast<float>(get_u32(f.data + 4));
      return DecodeError::kNone;
    }
    default:
      return DecodeError::kNotFeedback;
  }
}

CanFrame heartbeat(std::uint8_t node, const Heartbeat& h) {
  CanFrame f = frame(node, Command::kHeartbeat, 8);
  put_u32(f.data, h.axis_error);
  f.data[4] = h.axis_state;
  f.data[5] = h.motor_error ? 1 : 0;
  f.data[6] = h.encoder_error ? 1 : 0;
  f.data[7] = h.controller_error ? 1 : 0;
  return f;
}

CanFrame encoder_estimates(std::uint8_t node, const EncoderEstimates& e) {
  CanFrame f = frame(node, Command::kEncoderEstimates, 8);
  put_u32(f.data, std::bit_cast<std::uint32_t>(e.pos_turns));
  put_u32(f.data + 4, std::bit_cast<std::uint32_t>(e.vel_turns_per_s));
  return f;
}

DecodeError decode_command(const CanFrame& f, std::uint8_t node, CommandFrame& out) {
  if (f.extended) return DecodeError::kExtendedId;
  if ((f.id >> 5) != (node & kMaxNodeId)) return DecodeError::kOtherNode;
  const auto c = static_cast<Command>(f.id & 0x1F);
  out.command = c;
  switch (c) {
    case Command::kEstop:
    case Command::kClearErrors:
      return DecodeError::kNone;
    case Command::kSetAxisState:
      if (f.dlc < 4) return DecodeError::kWrongDlc;
      out.requested_state = get_u32(f.data);
      return DecodeError::kNone;
    case Command::kSetControllerMode:
      if (f.dlc != 8) return DecodeError::kWrongDlc;
      out.control_mode = static_cast<std::int32_t>(get_u32(f.data));
      out.input_mode = static_cast<std::int32_t>(get_u32(f.data + 4));
      return DecodeError::kNone;
    case Command::kSetInputVel:
      if (f.dlc != 8) return DecodeError::kWrongDlc;
      out.vel_turns_per_s = std::bit_cast<float>(get_u32(f.data));
      out.torque_ff_nm = std::bit_cast<float>(get_u32(f.data + 4));
      return DecodeError::kNone;
    default:
      return DecodeError::kNotFeedback;
  }
}

}  // namespace colag::hal::can::odrive
