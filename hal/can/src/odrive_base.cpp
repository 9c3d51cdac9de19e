#include "colag/hal/can/odrive_base.hpp"

#include <algorithm>
#include <cmath>

#include "colag/hal/can/diff_drive.hpp"

namespace colag::hal::can {

namespace {
bool in_error(const odrive::Heartbeat& b) {
  return b.axis_error != 0 || b.motor_error || b.encoder_error || b.controller_error;
}
}  // namespace

void OdriveBase::read_bus() {
  CanFrame f;
  while (bus_.receive(f)) {
    ++counters_.frames;
    for (Axis& a : axes_) {
      odrive::Feedback fb;
      const odrive::DecodeError e = odrive::decode(f, a.config.node, fb);
      if (e == odrive::DecodeError::kWrongDlc) ++counters_.bad_frames;
      if (e != odrive::DecodeError::kNone) continue;
      if (fb.command == odrive::Command::kHeartbeat) {
        ++counters_.heartbeats;
        a.beat = fb.heartbeat;
        if (a.heard == kNever) a.first_heard = f.stamp;
        a.heard = f.stamp;
      } else {
        on_estimates(a, fb.estimates, f.stamp);
      }
    }
  }
}

void OdriveBase::on_estimates(Axis& a, const odrive::EncoderEstimates& e, TimePoint stamp) {
  if (!std::isfinite(e.pos_turns)) {
    ++counters_.bad_frames;
    return;
  }
  ++counters_.estimates;
  a.pos_turns = a.config.direction * static_cast<double>(e.pos_turns);
  a.pos_stamp = stamp;
  if (!a.have_pos) a.used_turns = a.pos_turns;
  a.have_pos = a.fresh = true;
  if (axes_[0].fresh && axes_[1].fresh) make_sample();
}

void OdriveBase::make_sample() {
  // Both axes reported since the last sample: their positions are absolute, so a lost frame
  // loses no travel; the pair is stamped with the later of the two.
  const TimePoint stamp = std::max(axes_[0].pos_stamp, axes_[1].pos_stamp);
  axes_[0].fresh = axes_[1].fresh = false;
  if (!have_sample_pair_) {
    have_sample_pair_ = true;
    last_sample_ = stamp;
    return;
  }
  const double dt = to_seconds(stamp - last_sample_);
  if (!(dt > 0.0)) {
    ++counters_.implausible;  // time not advancing: keep the travel for the next pair
    return;
  }
  const double m = metres_per_motor_turn(config_, geometry_);
  const WheelPair travel{(axes_[0].pos_turns - axes_[0].used_turns) * m,
                         (axes_[1].pos_turns - axes_[1].used_turns) * m};
  WheelOdometrySample s;
  s.stamp = stamp;
  if (twist_from_travel(travel, dt, geometry_, s)) {
    if (pending_.push_overwrite(s)) ++counters_.overflowed;
    ++counters_.samples;
  } else {
    ++counters_.implausible;  // a jump (an axis rebooted, an encoder glitch): start again here
  }
  for (Axis& a : axes_)
    a.used_turns = a.pos_turns;
  last_sample_ = stamp;
}

bool OdriveBase::poll(WheelOdometrySample& out) {
  read_bus();
  return pending_.pop_front(out);
}

Status OdriveBase::send(const CanFrame& f, TimePoint now) {
  return bus_.send(f, now + kCommandSendWindow);
}

void OdriveBase::keep_in_closed_loop(TimePoint now) {
  const bool first = started_ == kNever;
  if (first) started_ = now;
  if (!first && !elapsed(now, last_request_, config_.request_period)) return;
  for (Axis& a : axes_) {
    const bool ready = a.beat.axis_state == odrive::kAxisStateClosedLoop && !in_error(a.beat);
    if (ready) a.was_ready = true;
    if (!first && ready) continue;
    // Errors left from the last run are cleared at start, and again at each request until the
    // axis has been ready once (the first clear may be lost: the ODrive still booting, a bus not
    // yet up), for ready_timeout after it is first heard. After that an error stays latched
    // until a person looks at it, except the watchdog's: it only says this host fell silent,
    // and the host is live again (a 200 ms stall must not end the mission; a trip left from the
    // last run only if errors are cleared at start).
    const bool starting =
        config_.clear_errors_at_start && !a.was_ready &&
        (first || a.heard == kNever || !elapsed(now, a.first_heard, config_.ready_timeout));
    const bool watchdog_only = a.beat.axis_error == odrive::kAxisErrorWatchdogExpired &&
                               !a.beat.motor_error && !a.beat.encoder_error &&
                               !a.beat.controller_error &&
                               (a.was_ready || config_.clear_errors_at_start);
    const bool clear = in_error(a.beat) ? (starting || watchdog_only) : (first && starting);
    if (in_error(a.beat) && !clear) continue;
    const std::uint8_t n = a.config.node;
    if (clear) {
      (void)send(odrive::clear_errors(n), now);
      if (!first && !starting) ++counters_.watchdog_clears;
      a.beat = {};  // its errors as last heard are the ones being cleared
    }
    (void)send(
        odrive::set_controller_mode(n, odrive::kControlModeVelocity, odrive::kInputModePassthrough),
        now);
    (void)send(odrive::set_axis_state(n, odrive::kAxisStateClosedLoop), now);
    ++counters_.closed_loop_requests;
    last_request_ = now;
  }
}

void OdriveBase::update_health(TimePoint now) {
  const bool past_start = elapsed(now, started_, config_.ready_timeout);
  health_ = {};
  if (bus_.stats().bus_off) {
    health_ = {msg::BaseFault::kBusOff, 0};
    return;
  }
  for (const Axis& a : axes_) {
    const bool silent = a.heard == kNever ? past_start : now - a.heard > config_.heartbeat_timeout;
    if (silent) {
      health_ = {msg::BaseFault::kBaseSilent, a.config.node};
      return;
    }
  }
  for (const Axis& a : axes_) {
    if (in_error(a.beat)) {
      health_ = {msg::BaseFault::kMotorError, a.beat.axis_error};
      return;
    }
  }
  for (const Axis& a : axes_) {
    if (past_start && a.beat.axis_state != odrive::kAxisStateClosedLoop) {
      health_ = {msg::BaseFault::kNotReady, a.beat.axis_state};
      return;
    }
  }
}

Status OdriveBase::send_velocities(TimePoint now, double left_mps, double right_mps) {
  const double per_turn = metres_per_motor_turn(config_, geometry_);
  const double v[2] = {left_mps, right_mps};
  Status result;
  for (int i = 0; i < 2; ++i) {
    const auto turns = static_cast<float>(axes_[i].config.direction * v[i] / per_turn);
    if (const Status s = send(odrive::set_input_vel(axes_[i].config.node, turns, 0.0F), now);
        !s && result)
      result = s;
  }
  return result;
}

Status OdriveBase::command(const DriveCommand& cmd) {
  keep_in_closed_loop(cmd.stamp);
  update_health(cmd.stamp);
  if (!std::isfinite(cmd.v_mps) || !std::isfinite(cmd.omega_radps)) {
    (void)send_velocities(cmd.stamp, 0.0, 0.0);
    return {Errc::kInvalidArgument, "drive command not finite: stopped"};
  }
  // A faulty base gets zero whatever is asked: it must not lurch when the fault clears.
  if (health_.fault != msg::BaseFault::kNone) return send_velocities(cmd.stamp, 0.0, 0.0);
  const WheelPair w = wheel_speeds(cmd, geometry_);
  return send_velocities(cmd.stamp, w.left, w.right);
}

Status OdriveBase::stop(TimePoint now) {
  keep_in_closed_loop(now);
  update_health(now);
  return send_velocities(now, 0.0, 0.0);
}

void OdriveBase::shutdown(TimePoint now) {
  (void)send_velocities(now, 0.0, 0.0);
  for (const Axis& a : axes_)
    (void)send(odrive::set_axis_state(a.config.node, odrive::kAxisStateIdle), now);
}

}  // namespace colag::hal::can
