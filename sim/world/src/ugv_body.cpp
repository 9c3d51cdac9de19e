#include "colag/sim/world/ugv_body.hpp"

#include <algorithm>
#include <cmath>

namespace colag::sim {

void UgvBody::step(TimePoint now, double dt, hal::CanBus& bus) {
  hal::can::WheelPair target = controller_.receive(now, bus);
  if (frozen_) {
    target = {};
    left_ = right_ = 0.0;
  }
  const double dv = config_.wheel_accel_mps2 * dt;
  const double wmax = config_.geometry.max_wheel_speed_mps;
  left_ = std::clamp(std::clamp(target.left, left_ - dv, left_ + dv), -wmax, wmax);
  right_ = std::clamp(std::clamp(target.right, right_ - dv, right_ + dv), -wmax, wmax);

  // True motion: the wheels' twist with 1 % multiplicative noise, integrated along the arc.
  const double b = config_.geometry.track_width_m;
  const bool moving = std::abs(left_) > 1e-3 || std::abs(right_) > 1e-3;
  double v = 0.5 * (left_ + right_), w = (right_ - left_) / b;
  if (moving) {
    v *= 1.0 + config_.motion_noise_fraction * rng_.gaussian();
    w *= 1.0 + config_.motion_noise_fraction * rng_.gaussian();
  }
  // The field world's wheels: the body slips against them, and the ground turns it.
  const WheelErrors& e = config_.wheel_errors;
  const bool field = e.any();
  const double wheel_left = moving ? left_ : 0.0, wheel_right = moving ? right_ : 0.0;
  if (field && moving) {
    const double accel = dt > 0.0 ? (0.5 * (left_ + right_) - last_v_) / dt : 0.0;
    v *= 1.0 - std::min(0.5, e.slip_per_mps2 * std::abs(accel));
    w = w * (1.0 - std::min(0.5, e.slip_per_radps * std::abs(w))) + e.yaw_rate_bias_radps;
  }
  last_v_ = 0.5 * (left_ + right_);
  const double th = pose_.yaw_rad;
  if (std::abs(w) > 1e-9) {
    pose_.p += Vec2(v / w * (std::sin(th + w * dt) - std::sin(th)),
                    -v / w * (std::cos(th + w * dt) - std::cos(th)));
  } else {
    pose_.p += v * dt * Vec2(std::cos(th), std::sin(th));
  }
  pose_.yaw_rad = wrap_angle(th + w * dt);
  travelled_ += std::abs(v) * dt;

  // Encoders: what the wheels did, plus the odometry noise while moving (correlated between
  // the wheels so that v and omega get exactly sigma_v and sigma_omega).
  double mv = v * (1.0 + config_.encoder_bias), mw = w * (1.0 + config_.encoder_bias);
  if (field) {
    // Each encoder counts its own wheel, with its own scale error; the body moved less.
    const double ml = wheel_left * (1.0 + e.left_scale), mr = wheel_right * (1.0 + e.right_scale);
    mv = 0.5 * (ml + mr) * (1.0 + config_.encoder_bias);
    mw = (mr - ml) / b * (1.0 + config_.encoder_bias);
  }
  if (moving) {
    mv += rng_.gaussian(0.0, config_.odometry_noise.sigma_v_mps);
    mw += rng_.gaussian(0.0, config_.odometry_noise.sigma_omega_radps);
  }
  controller_.report(now, {(mv - 0.5 * b * mw) * dt, (mv + 0.5 * b * mw) * dt}, {left_, right_},
                     bus);
}

}  // namespace colag::sim
