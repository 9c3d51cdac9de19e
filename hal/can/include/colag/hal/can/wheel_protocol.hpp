#pragma once
// The wheel-encoder / motor-controller CAN protocol (see hal/can/README.md): a pure codec.
#include <cstdint>

#include "colag/hal/can_bus.hpp"

namespace colag::hal::can {

struct WheelProtocolConfig {
  std::uint32_t counts_id = 0x101;
  std::uint32_t speeds_id = 0x102;
  std::uint32_t command_id = 0x201;
  bool extended_ids = false;
};

inline constexpr std::uint32_t kTickModulus = 1U << 24;

struct EncoderCounts {
  std::uint32_t left_ticks = 0;  // 24 bits used
  std::uint32_t right_ticks = 0;
  std::uint8_t alive = 0;
};
struct WheelSpeeds {
  std::int16_t left_mmps = 0;
  std::int16_t right_mmps = 0;
  std::uint8_t alive = 0;
};
struct SpeedCommand {
  std::int16_t left_mmps = 0;
  std::int16_t right_mmps = 0;
  bool enable = false;
  std::uint8_t alive = 0;
};

enum class FrameKind : std::uint8_t { kCounts, kSpeeds, kCommand };
enum class DecodeError : std::uint8_t { kNone, kUnknownId, kWrongDlc, kBadChecksum };

struct DecodedFrame {
  FrameKind kind = FrameKind::kCounts;
  EncoderCounts counts;
  WheelSpeeds speeds;
  SpeedCommand command;
};

// CRC-8/SAE-J1850 over `n` bytes.
std::uint8_t crc8(const std::uint8_t* data, std::size_t n);

CanFrame encode(const EncoderCounts& m, const WheelProtocolConfig& cfg);
CanFrame encode(const WheelSpeeds& m, const WheelProtocolConfig& cfg);
CanFrame encode(const SpeedCommand& m, const WheelProtocolConfig& cfg);
DecodeError decode(const CanFrame& frame, const WheelProtocolConfig& cfg, DecodedFrame& out);

// Signed difference of two 24-bit tick counters (the shorter way around the wrap).
std::int32_t tick_delta(std::uint32_t from, std::uint32_t to);

}  // namespace colag::hal::can
