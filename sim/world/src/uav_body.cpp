#include "colag/sim/world/uav_body.hpp"

#include <cmath>

namespace colag::sim {

UavBody::UavBody(const UavBodyConfig& config, const Vec3& start)
    : config_(config), frame_(config.odometry, start, config.seed) {
  state_.pose.p = start;
}

Status UavBody::send_setpoint(const hal::FlightSetpoint& sp) {
  if (!all_finite(sp.position_m) || !all_finite(sp.velocity_mps)) {
    return {Errc::kInvalidArgument, "flight setpoint not finite"};
  }
  setpoint_ = sp;
  have_setpoint_ = true;
  return Status::ok();
}

void UavBody::step(TimePoint now, double dt) {
  // Setpoints are in the odometry frame.
  Vec3 v_des = Vec3::Zero();  // no setpoint yet: hover
  if (have_setpoint_) v_des = frame_.vector_to_world(setpoint_.velocity_mps);
  if (v_des.head<2>().norm() > config_.v_max_mps)
    v_des.head<2>() *= config_.v_max_mps / v_des.head<2>().norm();
  Vec3 dv = v_des - state_.velocity_mps;
  const double max_dv = config_.a_max_mps2 * dt;
  if (dv.norm() > max_dv) dv *= max_dv / dv.norm();
  state_.velocity_mps += dv;
  state_.pose.p += state_.velocity_mps * dt;
  state_.stamp = now;
  travelled_ += state_.velocity_mps.norm() * dt;
  const UavOdometryErrors& e = config_.odometry;
  if (!e.any()) {
    pending_.push_overwrite(state_);
    return;
  }
  if (!borrowed_frame_) frame_.step(dt);  // a borrowed one is stepped by its owner
  hal::UavState measured = state_;
  measured.pose.p = frame_.to_odometry(state_.pose.p);
  measured.pose.q = frame_.turn() * state_.pose.q;
  measured.velocity_mps = frame_.vector_to_odometry(state_.velocity_mps);
  // Stamped when measured, delivered `latency` later.
  in_flight_.push_overwrite(measured);
  hal::UavState s;
  while (!in_flight_.empty() && in_flight_.front().stamp + e.latency <= now) {
    (void)in_flight_.pop_front(s);
    pending_.push_overwrite(s);
  }
}

}  // namespace colag::sim
