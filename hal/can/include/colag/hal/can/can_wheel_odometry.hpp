#pragma once
// The UGV's wheel odometry and drive on any CanBus (SocketCAN on a board, the simulated
// motor controller on the host): WheelOdometry from ENCODER_COUNTS frames, Drive as
// SPEED_COMMAND frames. Every malformed or implausible frame is rejected and counted.
#include <cmath>
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/hal/can/wheel_protocol.hpp"
#include "colag/hal/clock.hpp"
#include "colag/hal/drive.hpp"
#include "colag/hal/wheel_odometry.hpp"

namespace colag::hal::can {

struct WheelGeometry {
  double wheel_radius_m = 0.05;
  double track_width_m = 0.4;
  std::uint32_t ticks_per_revolution = 4096;
  double max_wheel_speed_mps = 0.7;
  std::int32_t max_ticks_per_frame = 20000;  // ~15 m/s for 20 ms frames: beyond is a fault
  double metres_per_turn() const { return 2.0 * M_PI * wheel_radius_m; }
  double metres_per_tick() const { return 2.0 * M_PI * wheel_radius_m / ticks_per_revolution; }
};

// How long every base driver lets the bus take to queue a command frame.
inline constexpr Duration kCommandSendWindow = std::chrono::milliseconds(5);

struct CanOdometryCounters {
  std::uint64_t frames = 0;
  std::uint64_t samples = 0;
  std::uint64_t unknown_id = 0;
  std::uint64_t wrong_dlc = 0;
  std::uint64_t bad_checksum = 0;
  std::uint64_t lost_frames = 0;  // alive-counter gaps
  std::uint64_t duplicates = 0;   // alive counter did not advance
  std::uint64_t implausible = 0;  // tick steps or speeds beyond the limits, or time not advancing
  std::uint64_t overflowed = 0;   // samples dropped because the task did not poll
};

class CanWheelOdometry final : public WheelOdometry {
 public:
  CanWheelOdometry(CanBus& bus, const WheelProtocolConfig& protocol, const WheelGeometry& geometry)
      : bus_(bus), protocol_(protocol), geometry_(geometry) {}

  bool poll(WheelOdometrySample& out) override;
  TimePoint last_sample_time() const override { return last_stamp_; }
  const CanOdometryCounters& counters() const { return counters_; }
  const WheelSpeeds& measured_speeds() const { return speeds_; }

 private:
  void read_bus();

  CanBus& bus_;
  WheelProtocolConfig protocol_;
  WheelGeometry geometry_;
  bool have_counts_ = false;
  EncoderCounts last_counts_{};
  TimePoint last_stamp_{};
  WheelSpeeds speeds_{};
  RingBuffer<WheelOdometrySample, limits::kOdometryBacklog> pending_;
  CanOdometryCounters counters_;
};

class CanDrive final : public Drive {
 public:
  CanDrive(CanBus& bus, const WheelProtocolConfig& protocol, const WheelGeometry& geometry)
      : bus_(bus), protocol_(protocol), geometry_(geometry) {}

  // (v, omega) -> wheel speeds, scaled together so that neither wheel exceeds its limit.
  Status command(const DriveCommand& cmd) override;
  Status stop(TimePoint now) override;
  DriveHealth health() const override;

 private:
  Status send(TimePoint now, double left_mps, double right_mps, bool enable);

  CanBus& bus_;
  WheelProtocolConfig protocol_;
  WheelGeometry geometry_;
  std::uint8_t alive_ = 0;
};

}  // namespace colag::hal::can
