#include "colag/hal/can/agilex_protocol.hpp"

namespace colag::hal::can::agilex {

namespace {

void put_be16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v);
}
void put_be32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    p[i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}
std::uint16_t be16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}
std::uint32_t be32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v = (v << 8) | p[i];
  return v;
}

CanFrame frame(std::uint32_t id) {
  CanFrame f;
  f.id = id;
  f.dlc = 8;
  return f;
}

CanFrame motion(std::uint32_t id, const MotionCommand& m) {
  CanFrame f = frame(id);
  put_be16(f.data, static_cast<std::uint16_t>(m.linear_mmps));
  put_be16(f.data + 2, static_cast<std::uint16_t>(m.angular_mradps));
  return f;  // lateral speed and steering angle (bytes 4..7) zero: a differential base
}

}  // namespace

CanFrame encode(const MotionCommand& m) {
  return motion(kMotionCommandId, m);
}

CanFrame encode_motion_state(const MotionState& m) {
  return motion(kMotionStateId, m);
}

CanFrame encode(const SystemState& m) {
  CanFrame f = frame(kSystemStateId);
  f.data[0] = m.vehicle_state;
  f.data[1] = m.control_mode;
  put_be16(f.data + 2, m.battery_dv);
  f.data[4] = m.fault;
  f.data[7] = m.count;
  return f;
}

CanFrame encode(const Odometry& m) {
  CanFrame f = frame(kOdometryId);
  put_be32(f.data, static_cast<std::uint32_t>(m.left_mm));
  put_be32(f.data + 4, static_cast<std::uint32_t>(m.right_mm));
  return f;
}

CanFrame control_mode(std::uint8_t mode) {
  CanFrame f = frame(kControlModeId);
  f.data[0] = mode;
  return f;
}

CanFrame state_reset() {
  return frame(kStateResetId);  // byte 0 = 0: clear every fault
}

DecodeError decode(const CanFrame& f, Decoded& out) {
  if (f.extended) return DecodeError::kExtendedId;
  switch (f.id) {
    case kMotionCommandId:
    case kMotionStateId:
    case kSystemStateId:
    case kOdometryId:
    case kControlModeId:
    case kStateResetId:
      break;
    default:
      return DecodeError::kUnknownId;
  }
  // Every V2 frame is 8 bytes; the mode and reset commands are read from their first byte.
  const bool short_ok = f.id == kControlModeId || f.id == kStateResetId;
  if (short_ok ? f.dlc < 1 : f.dlc != 8) return DecodeError::kWrongDlc;
  out.id = f.id;
  switch (f.id) {
    case kMotionCommandId:
    case kMotionStateId:
      out.motion.linear_mmps = static_cast<std::int16_t>(be16(f.data));
      out.motion.angular_mradps = static_cast<std::int16_t>(be16(f.data + 2));
      break;
    case kSystemStateId:
      out.system.vehicle_state = f.data[0];
      out.system.control_mode = f.data[1];
      out.system.battery_dv = be16(f.data + 2);
      out.system.fault = f.data[4];
      out.system.count = f.data[7];
      break;
    case kOdometryId:
      out.odometry.left_mm = static_cast<std::int32_t>(be32(f.data));
      out.odometry.right_mm = static_cast<std::int32_t>(be32(f.data + 4));
      break;
    default:
      out.mode = f.data[0];
      break;
  }
  return DecodeError::kNone;
}

}  // namespace colag::hal::can::agilex
