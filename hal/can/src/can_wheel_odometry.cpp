#include "colag/hal/can/can_wheel_odometry.hpp"

#include "colag/hal/can/diff_drive.hpp"

#include <algorithm>
#include <cmath>

namespace colag::hal::can {

void CanWheelOdometry::read_bus() {
  CanFrame f;
  while (bus_.receive(f)) {
    ++counters_.frames;
    DecodedFrame d;
    switch (decode(f, protocol_, d)) {
      case DecodeError::kUnknownId:
        ++counters_.unknown_id;
        continue;
      case DecodeError::kWrongDlc:
        ++counters_.wrong_dlc;
        continue;
      case DecodeError::kBadChecksum:
        ++counters_.bad_checksum;
        continue;
      case DecodeError::kNone:
        break;
    }
    if (d.kind == FrameKind::kSpeeds) {
      speeds_ = d.speeds;
      continue;
    }
    if (d.kind != FrameKind::kCounts) continue;  // our own commands echoed back
    const EncoderCounts& c = d.counts;
    if (have_counts_ && c.alive == last_counts_.alive) {
      ++counters_.duplicates;  // the same frame again (or a stuck controller)
      continue;
    }
    if (have_counts_) {
      const auto gap = static_cast<std::uint8_t>(c.alive - last_counts_.alive - 1);
      counters_.lost_frames += gap;
      const std::int32_t dl = tick_delta(last_counts_.left_ticks, c.left_ticks);
      const std::int32_t dr = tick_delta(last_counts_.right_ticks, c.right_ticks);
      const double dt = to_seconds(f.stamp - last_stamp_);
      const std::int32_t limit = geometry_.max_ticks_per_frame * (gap + 1);
      const double m_per_tick = geometry_.metres_per_tick();
      WheelOdometrySample s;
      s.stamp = f.stamp;
      if (std::abs(dl) > limit || std::abs(dr) > limit ||
          !twist_from_travel({dl * m_per_tick, dr * m_per_tick}, dt, geometry_, s)) {
        ++counters_.implausible;
      } else {
        if (pending_.push_overwrite(s)) ++counters_.overflowed;
        ++counters_.samples;
      }
    }
    have_counts_ = true;
    last_counts_ = c;
    last_stamp_ = f.stamp;
  }
}

bool CanWheelOdometry::poll(WheelOdometrySample& out) {
  read_bus();
  return pending_.pop_front(out);
}

Status CanDrive::send(TimePoint now, double left, double right, bool enable) {
  SpeedCommand cmd;
  cmd.left_mmps = static_cast<std::int16_t>(std::lround(std::clamp(left, -30.0, 30.0) * 1000.0));
  cmd.right_mmps = static_cast<std::int16_t>(std::lround(std::clamp(right, -30.0, 30.0) * 1000.0));
  cmd.enable = enable;
  cmd.alive = alive_++;
  return bus_.send(encode(cmd, protocol_), now + kCommandSendWindow);
}

Status CanDrive::command(const DriveCommand& cmd) {
  if (!std::isfinite(cmd.v_mps) || !std::isfinite(cmd.omega_radps)) {
    (void)stop(cmd.stamp);
    return {Errc::kInvalidArgument, "drive command not finite: stopped"};
  }
  const WheelPair w = wheel_speeds(cmd, geometry_);
  return send(cmd.stamp, w.left, w.right, true);
}

Status CanDrive::stop(TimePoint now) {
  return send(now, 0.0, 0.0, true);
}

DriveHealth CanDrive::health() const {
  // The motor controller of this protocol has no fault report: the wheel odometry's watchdog
  // (in the task) and the bus's own state are what the firmware can know.
  if (bus_.stats().bus_off) return {msg::BaseFault::kBusOff, 0};
  return {};
}

}  // namespace colag::hal::can
