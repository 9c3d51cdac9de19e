#include "colag/hal/can/agilex_base.hpp"

#include <algorithm>
#include <cmath>

#include "colag/hal/can/diff_drive.hpp"

namespace colag::hal::can {

namespace {
std::int16_t to_i16(double v) {
  return static_cast<std::int16_t>(std::lround(std::clamp(v, -32767.0, 32767.0)));
}
}  // namespace

void AgilexBase::read_bus() {
  CanFrame f;
  while (bus_.receive(f)) {
    ++counters_.frames;
    agilex::Decoded d;
    const agilex::DecodeError e = agilex::decode(f, d);
    if (e == agilex::DecodeError::kWrongDlc) ++counters_.bad_frames;
    if (e != agilex::DecodeError::kNone) continue;
    if (d.id == agilex::kSystemStateId) {
      if (heard_ != kNever)
        counters_.lost_states += static_cast<std::uint8_t>(d.system.count - state_.count - 1);
      ++counters_.states;
      state_ = d.system;
      heard_ = f.stamp;
      continue;
    }
    if (d.id != agilex::kOdometryId) continue;  // motion state: the odometry says it better
    if (have_odometry_) {
      // Unsigned difference: the 32-bit millimetre counters may wrap.
      const auto dl = static_cast<std::int32_t>(static_cast<std::uint32_t>(d.odometry.left_mm) -
                                                static_cast<std::uint32_t>(last_odometry_.left_mm));
      const auto dr =
          static_cast<std::int32_t>(static_cast<std::uint32_t>(d.odometry.right_mm) -
                                    static_cast<std::uint32_t>(last_odometry_.right_mm));
      WheelOdometrySample s;
      s.stamp = f.stamp;
      const WheelPair travel{config_.left_sign * dl * 1e-3, config_.right_sign * dr * 1e-3};
      if (twist_from_travel(travel, to_seconds(f.stamp - last_stamp_), geometry_, s)) {
        if (pending_.push_overwrite(s)) ++counters_.overflowed;
        ++counters_.samples;
      } else {
        ++counters_.implausible;
      }
    }
    have_odometry_ = true;
    last_odometry_ = d.odometry;
    last_stamp_ = f.stamp;
  }
}

bool AgilexBase::poll(WheelOdometrySample& out) {
  read_bus();
  return pending_.pop_front(out);
}

void AgilexBase::keep_in_can_mode(TimePoint now) {
  const bool first = started_ == kNever;
  if (first) {
    started_ = now;
    if (config_.clear_errors_at_start)
      (void)bus_.send(agilex::state_reset(), now + kCommandSendWindow);
  } else if (state_.control_mode == agilex::kControlModeCan ||
             !elapsed(now, last_request_, config_.request_period)) {
    return;
  }
  (void)bus_.send(agilex::control_mode(agilex::kControlModeCan), now + kCommandSendWindow);
  ++counters_.mode_requests;
  last_request_ = now;
}

void AgilexBase::update_health(TimePoint now) {
  const bool past_start = elapsed(now, started_, config_.ready_timeout);
  const bool silent = heard_ == kNever ? past_start : now - heard_ > config_.state_timeout;
  health_ = {};  // also while starting: nothing heard yet, not yet late
  if (bus_.stats().bus_off) {
    health_ = {msg::BaseFault::kBusOff, 0};
  } else if (silent) {
    health_ = {msg::BaseFault::kBaseSilent, 0};
  } else if (heard_ == kNever) {
    return;
  } else if (state_.vehicle_state == agilex::kVehicleEstop) {
    health_ = {msg::BaseFault::kEstop, state_.fault};
  } else if ((state_.fault & agilex::kFaultBatteryLow) != 0) {
    health_ = {msg::BaseFault::kLowBattery, state_.fault};
  } else if (state_.vehicle_state != agilex::kVehicleNormal) {
    health_ = {msg::BaseFault::kMotorError, state_.fault};
  } else if (past_start && state_.control_mode != agilex::kControlModeCan) {
    health_ = {msg::BaseFault::kNotReady, state_.control_mode};
  }
}

Status AgilexBase::send_motion(TimePoint now, double v, double omega) {
  agilex::MotionCommand m;
  m.linear_mmps = to_i16(v * 1000.0);
  m.angular_mradps = to_i16(omega * 1000.0);
  return bus_.send(agilex::encode(m), now + kCommandSendWindow);
}

Status AgilexBase::command(const DriveCommand& cmd) {
  keep_in_can_mode(cmd.stamp);
  update_health(cmd.stamp);
  if (!std::isfinite(cmd.v_mps) || !std::isfinite(cmd.omega_radps)) {
    (void)send_motion(cmd.stamp, 0.0, 0.0);
    return {Errc::kInvalidArgument, "drive command not finite: stopped"};
  }
  if (health_.fault != msg::BaseFault::kNone) return send_motion(cmd.stamp, 0.0, 0.0);
  // The wheels' limit first (the turn is kept, the speed gives way), then the base's own.
  DriveCommand c = cmd;
  c.omega_radps = std::clamp(c.omega_radps, -config_.max_angular_radps, config_.max_angular_radps);
  const WheelPair w = wheel_speeds(c, geometry_);
  return send_motion(cmd.stamp, 0.5 * (w.left + w.right),
                     (w.right - w.left) / geometry_.track_width_m);
}

Status AgilexBase::stop(TimePoint now) {
  keep_in_can_mode(now);
  update_health(now);
  return send_motion(now, 0.0, 0.0);
}

}  // namespace colag::hal::can
