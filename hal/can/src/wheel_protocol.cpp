#include "colag/hal/can/wheel_protocol.hpp"

namespace colag::hal::can {

namespace {

void put_u24(std::uint8_t* p, std::uint32_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
  p[2] = static_cast<std::uint8_t>(v >> 16);
}
std::uint32_t get_u24(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16;
}
void put_i16(std::uint8_t* p, std::int16_t v) {
  const auto u = static_cast<std::uint16_t>(v);
  p[0] = static_cast<std::uint8_t>(u);
  p[1] = static_cast<std::uint8_t>(u >> 8);
}
std::int16_t get_i16(const std::uint8_t* p) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] | p[1] << 8));
}

CanFrame frame(std::uint32_t id, const WheelProtocolConfig& cfg, std::uint8_t alive) {
  CanFrame f;
  f.id = id;
  f.extended = cfg.extended_ids;
  f.dlc = 8;
  f.data[6] = alive;
  return f;
}
void seal(CanFrame& f) {
  f.data[7] = crc8(f.data, 7);
}

}  // namespace

std::uint8_t crc8(const std::uint8_t* data, std::size_t n) {
  std::uint8_t crc = 0xFF;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int b = 0; b < 8; ++b)
      crc = static_cast<std::uint8_t>((crc & 0x80) ? (crc << 1) ^ 0x1D : crc << 1);
  }
  return static_cast<std::uint8_t>(crc ^ 0xFF);
}

CanFrame encode(const EncoderCounts& m, const WheelProtocolConfig& cfg) {
  CanFrame f = frame(cfg.counts_id, cfg, m.alive);
  put_u24(f.data, m.left_ticks % kTickModulus);
  put_u24(f.data + 3, m.right_ticks % kTickModulus);
  seal(f);
  return f;
}

CanFrame encode(const WheelSpeeds& m, const WheelProtocolConfig& cfg) {
  CanFrame f = frame(cfg.speeds_id, cfg, m.alive);
  put_i16(f.data, m.left_mmps);
  put_i16(f.data + 2, m.right_mmps);
  seal(f);
  return f;
}

CanFrame encode(const SpeedCommand& m, const WheelProtocolConfig& cfg) {
  CanFrame f = frame(cfg.command_id, cfg, m.alive);
  put_i16(f.data, m.left_mmps);
  put_i16(f.data + 2, m.right_mmps);
  f.data[4] = m.enable ? 1 : 0;
  seal(f);
  return f;
}

DecodeError decode(const CanFrame& f, const WheelProtocolConfig& cfg, DecodedFrame& out) {
  if (f.extended != cfg.extended_ids ||
      (f.id != cfg.counts_id && f.id != cfg.speeds_id && f.id != cfg.command_id)) {
    return DecodeError::kUnknownId;
  }
  if (f.dlc != 8) return DecodeError::kWrongDlc;
  if (crc8(f.data, 7) != f.data[7]) return DecodeError::kBadChecksum;
  if (f.id == cfg.counts_id) {
    out.kind = FrameKind::kCounts;
    out.counts = {get_u24(f.data), get_u24(f.data + 3), f.data[6]};
  } else if (f.id == cfg.speeds_id) {
    out.kind = FrameKind::kSpeeds;
    out.speeds = {get_i16(f.data), get_i16(f.data + 2), f.data[6]};
  } else {
    out.kind = FrameKind::kCommand;
    out.command = {get_i16(f.data), get_i16(f.data + 2), (f.data[4] & 1) != 0, f.data[6]};
  }
  return DecodeError::kNone;
}

std::int32_t tick_delta(std::uint32_t from, std::uint32_t to) {
  const std::uint32_t d = (to - from) & (kTickModulus - 1);
  return d >= kTickModulus / 2
             ? static_cast<std::int32_t>(d) - static_cast<std::int32_t>(kTickModulus)
             : static_cast<std::int32_t>(d);
}

}  // namespace colag::hal::can
