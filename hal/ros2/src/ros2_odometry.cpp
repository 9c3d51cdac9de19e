#include <cmath>

#include "colag/hal/dds/take_one.hpp"
#include "colag/hal/ros2/ros2_devices.hpp"
#include "ros2_msgs.h"

namespace colag::hal::ros2 {

bool Ros2Odometry::init(const Ros2OdometryConfig& config, std::string& error) {
  config_ = config;
  if (!dds_.init(config.dds_domain)) {
    error =
        "odometry on DDS domain " + std::to_string(config.dds_domain) + ": " + dds_.last_error();
    return false;
  }
  reader_ = dds_.reader(ros2_dds_topic(config.topic), nav_msgs_msg_dds__Odometry__desc, 4);
  if (!reader_) {
    error = "odometry: " + dds_.last_error();
    return false;
  }
  return true;
}

bool Ros2Odometry::poll(UavState& out) {
  bool got = false;
  while (dds::take_one<nav_msgs_msg_dds__Odometry_>(reader_, [&](const auto& m) {
    ++counters_.received;
    const auto& pp = m.pose.pose.position;
    const auto& pq = m.pose.pose.orientation;
    const Vec3 p(pp.x, pp.y, pp.z);
    const Quat q(pq.w, pq.x, pq.y, pq.z);
    if (!all_finite(p) || !q.coeffs().allFinite() || q.norm() < 0.5) {
      ++counters_.rejected;
      return;
    }
    UavState s;
    s.stamp = clock_.now() - config_.latency;
    s.pose = config_.origin.compose(Pose3{p, q.normalized()}).compose(config_.body_to_uav);
    // The twist is in the child frame (REP-105); FAST-LIO leaves it zero.
    const auto& tl = m.twist.twist.linear;
    const auto& ta = m.twist.twist.angular;
    const Vec3 v_child(tl.x, tl.y, tl.z), w_child(ta.x, ta.y, ta.z);
    const Quat q_child = (config_.origin.q * q.normalized()).normalized();
    // The pose's rate of change, where the twist is empty: over a sane interval only.
    const double dt = have_last_ ? to_seconds(s.stamp - last_.stamp) : 0.0;
    const bool differentiate = dt > 1e-3 && dt < 0.5;
    if (all_finite(v_child) && v_child.squaredNorm() > 0.0) {
      velocity_ = q_child * v_child;
    } else if (differentiate) {  // smoothed over ~3 samples
      velocity_ += 0.3 * ((s.pose.p - last_.pose.p) / dt - velocity_);
    }
    s.velocity_mps = velocity_;
    if (all_finite(w_child) && w_child.squaredNorm() > 0.0) {
      s.yaw_rate_radps = (q_child * w_child).z();
    } else if (differentiate) {
      s.yaw_rate_radps = wrap_angle(yaw_of(s.pose.q) - yaw_of(last_.pose.q)) / dt;
    }
    last_ = s;
    have_last_ = true;
    out = s;
    got = true;
  })) {
  }
  return got;
}

}  // namespace colag::hal::ros2
