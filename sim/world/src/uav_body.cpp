#include "colag/sim/world/uav_body.hpp"

#include <cmath>

namespace colag::sim {

Status UavBody::send_setpoint(const hal::FlightSetpoint& sp) {
  if (!all_finite(sp.position_m) || !all_finite(sp.velocity_mps)) {
    return {Errc::kInvalidArgument, "flight setpoint not finite"};
  }
  setpoint_ = sp;
  have_setpoint_ = true;
  return Status::ok();
}

void UavBody::step(TimePoint now, double dt) {
  Vec3 v_des = Vec3::Zero();  // no setpoint yet: hover
  if (have_setpoint_) v_des = setpoint_.velocity_mps;
  if (v_des.head<2>().norm() > config_.v_max_mps)
    v_des.head<2>() *= config_.v_max_mps / v_des.head<2>().norm();
  Vec3 dv = v_des - state_.velocity_mps;
  const double max_dv = config_.a_max_mps2 * dt;
  if (dv.norm() > max_dv) dv *= max_dv / dv.norm();
  state_.velocity_mps += dv;
  state_.pose.p += state_.velocity_mps * dt;
  state_.stamp = now;
  travelled_ += state_.velocity_mps.norm() * dt;
  pending_.push_overwrite(state_);
}

}  // namespace colag::sim
