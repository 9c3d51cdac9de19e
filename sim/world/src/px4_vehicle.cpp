#include "colag/sim/world/px4_vehicle.hpp"

namespace colag::sim {

namespace {
constexpr std::uint32_t kNavLandCmd = 21, kSetMode = 176, kArmDisarm = 400;
}  // namespace

void Px4Vehicle::on_heartbeat(TimePoint now) {
  if (stream_since_ == kNever || now - last_heartbeat_ > config_.offboard_loss_timeout)
    stream_since_ = now;
  last_heartbeat_ = now;
}

void Px4Vehicle::on_setpoint(TimePoint now, const hal::FlightSetpoint& sp) {
  (void)now;
  setpoint_ = sp;
  have_setpoint_ = true;
}

bool Px4Vehicle::stream_ready(TimePoint now) const {
  return stream_since_ != kNever && now - last_heartbeat_ <= config_.offboard_loss_timeout &&
         now - stream_since_ >= config_.offboard_stream_needed && have_setpoint_;
}

std::uint8_t Px4Vehicle::on_command(TimePoint now, std::uint32_t command, float param1,
                                    float param2) {
  switch (command) {
    case kSetMode:
      if (param1 != 1.0F || param2 != 6.0F) return kUnsupported;  // only offboard is played
      if (!stream_ready(now)) return kTemporarilyRejected;
      nav_state_ = kNavOffboard;
      failsafe_ = false;
      holding_ = false;
      return kAccepted;
    case kArmDisarm:
      if (param1 == 0.0F) {
        armed_ = false;
        return kAccepted;
      }
      if (failsafe_) return kDenied;
      armed_ = true;
      return kAccepted;
    case kNavLandCmd:
      if (!armed_) return kDenied;
      nav_state_ = kNavLand;
      return kAccepted;
    default:
      return kUnsupported;
  }
}

void Px4Vehicle::hold(const Vec3& at) {
  if (!holding_) hold_at_ = at;
  holding_ = true;
}

void Px4Vehicle::fail_safe(const Vec3& position) {
  failsafe_ = true;
  nav_state_ = kNavLoiter;
  holding_ = false;
  hold(position);
}

void Px4Vehicle::pilot_takes_over(const Vec3& position) {
  nav_state_ = kNavPosition;
  holding_ = false;
  hold(position);
}

void Px4Vehicle::step(TimePoint now, const Vec3& position) {
  hal::FlightSetpoint out;
  out.stamp = now;
  out.position_m = position;
  if (!armed_) {
    (void)body_.send_setpoint(out);  // on the ground: motors off
    return;
  }
  if (nav_state_ == kNavOffboard && now - last_heartbeat_ > config_.offboard_loss_timeout) {
    fail_safe(position);  // offboard lost: COM_OBL_RC_ACT = hold
  }
  switch (nav_state_) {
    case kNavOffboard:
      out = setpoint_;
      out.stamp = now;
      // Its position loop: the setpoint's velocity is the feed-forward.
      out.velocity_mps =
          setpoint_.velocity_mps + config_.hold_gain * (setpoint_.position_m - position);
      break;
    case kNavLand:
      out.velocity_mps = Vec3(0.0, 0.0, -config_.land_speed_mps);
      if (position.z() <= config_.ground_z_m + 0.05) {  // touched down: PX4 disarms itself
        armed_ = false;
        nav_state_ = kNavLoiter;
        out.velocity_mps = Vec3::Zero();
      }
      break;
    default:
      hold(position);
      out.position_m = hold_at_;
      out.velocity_mps = config_.hold_gain * (hold_at_ - position);
      break;
  }
  if (out.velocity_mps.norm() > config_.v_max_mps)
    out.velocity_mps *= config_.v_max_mps / out.velocity_mps.norm();
  (void)body_.send_setpoint(out);
}

}  // namespace colag::sim
