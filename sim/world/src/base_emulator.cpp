#include "colag/sim/world/base_emulator.hpp"

#include <algorithm>
#include <cmath>

#include "colag/hal/can/agilex_protocol.hpp"
#include "colag/hal/can/odrive_protocol.hpp"

namespace colag::sim {

using hal::can::BaseProtocol;
using hal::can::WheelPair;
namespace odrive = hal::can::odrive;
namespace agilex = hal::can::agilex;

namespace {
constexpr Duration kOdriveHeartbeatPeriod = std::chrono::milliseconds(100);
}

BaseEmulator::BaseEmulator(const hal::can::BaseConfig& config,
                           const hal::can::WheelGeometry& geometry, Duration command_timeout)
    : config_(config), geometry_(geometry), command_timeout_(command_timeout) {
  axes_[0].config = config.odrive.left;
  axes_[1].config = config.odrive.right;
}

void BaseEmulator::set_fault(bool on) {
  fault_ = on;
  if (on && config_.protocol == BaseProtocol::kOdrive) {
    axes_[0].error |= odrive::kAxisErrorMotorFailed;
    axes_[0].state = odrive::kAxisStateIdle;
  }
}

bool BaseEmulator::driving() const {
  switch (config_.protocol) {
    case BaseProtocol::kColag:
      return !fault_;
    case BaseProtocol::kOdrive:
      return axes_[0].state == odrive::kAxisStateClosedLoop &&
             axes_[1].state == odrive::kAxisStateClosedLoop;
    case BaseProtocol::kAgilexV2:
      return !fault_ && agilex_mode_ == agilex::kControlModeCan;
  }
  return false;
}

void BaseEmulator::receive_colag(const hal::CanFrame& f) {
  hal::can::DecodedFrame d;
  if (hal::can::decode(f, config_.colag, d) != hal::can::DecodeError::kNone) return;
  if (d.kind != hal::can::FrameKind::kCommand) return;
  target_.left = d.command.enable ? d.command.left_mmps / 1000.0 : 0.0;
  target_.right = d.command.enable ? d.command.right_mmps / 1000.0 : 0.0;
  last_command_ = f.stamp;
}

void BaseEmulator::receive_odrive(const hal::CanFrame& f) {
  for (OdriveAxis& a : axes_) {
    odrive::CommandFrame c;
    const odrive::DecodeError e = odrive::decode_command(f, a.config.node, c);
    if (e == odrive::DecodeError::kOtherNode || e == odrive::DecodeError::kExtendedId) continue;
    a.fed = f.stamp;  // any frame to the axis feeds its watchdog
    if (e != odrive::DecodeError::kNone) continue;
    switch (c.command) {
      case odrive::Command::kSetAxisState:
        if (c.requested_state == odrive::kAxisStateIdle) {
          a.state = odrive::kAxisStateIdle;
        } else if (c.requested_state == odrive::kAxisStateClosedLoop && a.error == 0) {
          a.state = odrive::kAxisStateClosedLoop;
          a.input_turns_per_s = 0.0F;
        }
        break;
      case odrive::Command::kSetInputVel:
        if (std::isfinite(c.vel_turns_per_s)) a.input_turns_per_s = c.vel_turns_per_s;
        break;
      case odrive::Command::kEstop:
        a.error |= odrive::kAxisErrorEstopRequested;
        a.state = odrive::kAxisStateIdle;
        break;
      case odrive::Command::kClearErrors:
        a.error = 0;
        break;
      default:
        break;
    }
  }
}

void BaseEmulator::receive_agilex(const hal::CanFrame& f) {
  agilex::Decoded d;
  if (agilex::decode(f, d) != agilex::DecodeError::kNone) return;
  if (d.id == agilex::kControlModeId) {
    agilex_mode_ =
        d.mode == agilex::kControlModeCan ? agilex::kControlModeCan : agilex::kControlModeRc;
  } else if (d.id == agilex::kMotionCommandId && agilex_mode_ == agilex::kControlModeCan) {
    const hal::DriveCommand c{f.stamp, d.motion.linear_mmps / 1000.0,
                              d.motion.angular_mradps / 1000.0};
    target_ = hal::can::wheel_speeds(c, geometry_);
    last_command_ = f.stamp;
  }
}

WheelPair BaseEmulator::odrive_targets(TimePoint now) {
  const double m_per_turn = hal::can::metres_per_motor_turn(config_.odrive, geometry_);
  double v[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    OdriveAxis& a = axes_[i];
    if (a.state == odrive::kAxisStateClosedLoop && elapsed(now, a.fed, command_timeout_)) {
      a.error |= odrive::kAxisErrorWatchdogExpired;
      a.state = odrive::kAxisStateIdle;
    }
    if (a.state == odrive::kAxisStateClosedLoop)
      v[i] = a.config.direction * static_cast<double>(a.input_turns_per_s) * m_per_turn;
  }
  return {v[0], v[1]};
}

WheelPair BaseEmulator::receive(TimePoint now, hal::CanBus& bus) {
  hal::CanFrame f;
  while (bus.receive(f)) {
    switch (config_.protocol) {
      case BaseProtocol::kColag:
        receive_colag(f);
        break;
      case BaseProtocol::kOdrive:
        receive_odrive(f);
        break;
      case BaseProtocol::kAgilexV2:
        receive_agilex(f);
        break;
    }
  }
  if (config_.protocol == BaseProtocol::kOdrive) return odrive_targets(now);
  if (elapsed(now, last_command_, command_timeout_) || fault_ ||
      (config_.protocol == BaseProtocol::kAgilexV2 && agilex_mode_ != agilex::kControlModeCan))
    target_ = {};
  return target_;
}

void BaseEmulator::report(TimePoint now, const WheelPair& step_m, const WheelPair& speeds,
                          hal::CanBus& bus) {
  switch (config_.protocol) {
    case BaseProtocol::kColag: {
      if (fault_) return;  // this controller has no fault report: it goes silent
      const double m_per_tick = geometry_.metres_per_tick();
      ticks_left_ += step_m.left / m_per_tick;
      ticks_right_ += step_m.right / m_per_tick;
      const auto wrap = [](double t) {
        const auto i = static_cast<std::int64_t>(std::floor(t));
        return static_cast<std::uint32_t>(((i % hal::can::kTickModulus) + hal::can::kTickModulus) %
                                          hal::can::kTickModulus);
      };
      (void)bus.send(hal::can::encode(hal::can::EncoderCounts{wrap(ticks_left_), wrap(ticks_right_),
                                                              alive_counts_++},
                                      config_.colag),
                     now);
      hal::can::WheelSpeeds w;
      w.left_mmps = static_cast<std::int16_t>(std::lround(speeds.left * 1000.0));
      w.right_mmps = static_cast<std::int16_t>(std::lround(speeds.right * 1000.0));
      w.alive = alive_speeds_++;
      (void)bus.send(hal::can::encode(w, config_.colag), now);
      return;
    }
    case BaseProtocol::kOdrive: {
      const double turns_per_m = 1.0 / hal::can::metres_per_motor_turn(config_.odrive, geometry_);
      const double step[2] = {step_m.left, step_m.right};
      const double speed[2] = {speeds.left, speeds.right};
      const bool beat = elapsed(now, last_heartbeat_, kOdriveHeartbeatPeriod);
      if (beat) last_heartbeat_ = now;
      for (int i = 0; i < 2; ++i) {
        OdriveAxis& a = axes_[i];
        a.pos_turns += a.config.direction * step[i] * turns_per_m;
        const odrive::EncoderEstimates e{
            static_cast<float>(a.pos_turns),
            static_cast<float>(a.config.direction * speed[i] * turns_per_m)};
        (void)bus.send(odrive::encoder_estimates(a.config.node, e), now);
        if (beat) {
          odrive::Heartbeat h;
          h.axis_error = a.error;
          h.axis_state = static_cast<std::uint8_t>(a.state);
          h.motor_error = (a.error & odrive::kAxisErrorMotorFailed) != 0;
          (void)bus.send(odrive::heartbeat(a.config.node, h), now);
        }
      }
      return;
    }
    case BaseProtocol::kAgilexV2: {
      agilex_left_mm_ += config_.agilex.left_sign * step_m.left * 1000.0;
      agilex_right_mm_ += config_.agilex.right_sign * step_m.right * 1000.0;
      agilex::SystemState s;
      s.vehicle_state = fault_ ? agilex::kVehicleEstop : agilex::kVehicleNormal;
      s.control_mode = agilex_mode_;
      s.battery_dv = 252;
      s.count = agilex_count_++;
      (void)bus.send(agilex::encode(s), now);
      agilex::MotionState m;
      m.linear_mmps = static_cast<std::int16_t>(std::lround(500.0 * (speeds.left + speeds.right)));
      m.angular_mradps = static_cast<std::int16_t>(
          std::lround(1000.0 * (speeds.right - speeds.left) / geometry_.track_width_m));
      (void)bus.send(agilex::encode_motion_state(m), now);
      const auto mm = [](double v) {
        return static_cast<std::int32_t>(std::llround(std::floor(v)));
      };
      (void)bus.send(agilex::encode(agilex::Odometry{mm(agilex_left_mm_), mm(agilex_right_mm_)}),
                     now);
      return;
    }
  }
}

}  // namespace colag::sim
