#pragma once
// A simulated differential-drive UGV and its motor controllers. The controllers speak the base's
// real CAN protocol (BaseEmulator: ours, ODrive or AgileX): they take its commands (zero after
// 200 ms without one), drive the wheels towards them within the acceleration limit, and report
// the protocol's feedback every step (50 Hz). The true motion gets 1 % multiplicative noise on v
// and omega (the paper's simulation); the encoders measure it with white noise sigma_v, sigma_omega
// per sample (the paper's odometry noise), applied only while the wheels turn.
#include "colag/common/random.hpp"
#include "colag/common/ugv_motion_model.hpp"
#include "colag/hal/can/base_config.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/sim/world/base_emulator.hpp"

namespace colag::sim {

// What real wheels do that the EKF's model does not (the field world; all zero in the ideal
// one): each encoder's scale off (a tyre worn or inflated differently, a wrong nominal radius:
// both a distance and a track error), the body slipping more the harder it turns or
// accelerates (skid steering), and the ground turning it a little (camber, a slope).
struct WheelErrors {
  double left_scale = 0.0;  // the left encoder reports (1 + left_scale) x the wheel's motion
  double right_scale = 0.0;
  double slip_per_radps = 0.0;  // the body's turn rate is (1 - k |omega|) x the wheels'
  double slip_per_mps2 = 0.0;   // its speed is (1 - k |accel|) x the wheels'
  double yaw_rate_bias_radps = 0.0;
  bool any() const {
    return left_scale != 0.0 || right_scale != 0.0 || slip_per_radps != 0.0 ||
           slip_per_mps2 != 0.0 || yaw_rate_bias_radps != 0.0;
  }
};

struct UgvBodyConfig {
  double radius_m = 0.25;
  double height_m = 0.3;  // the body's top (the AprilTag lies on it): what sensors see of it
  // What counts as touching an obstacle: one reaching into the firmware's body band (lower
  // clutter is driven over, higher obstacles passed under). The band is the one the UAV maps
  // and the UGV keeps clear, a little above the body's top: a conservative collision test.
  double band_low_m = 0.1;
  double band_high_m = 0.7;
  hal::can::BaseConfig base;  // the protocol its controllers speak
  hal::can::WheelGeometry geometry;
  double wheel_accel_mps2 = 1.0;
  double motion_noise_fraction = 0.01;
  OdometryNoise odometry_noise;  // sigma_v, sigma_omega used; fractions ignored
  Duration command_timeout = std::chrono::milliseconds(200);
  double encoder_bias = 0.0;  // fault injection: encoders report (1 + bias) x the wheels' motion
  WheelErrors wheel_errors;   // the field world's wheels (per UGV)
};

class UgvBody {
 public:
  UgvBody(const UgvBodyConfig& config, const Pose2& start, std::uint64_t seed)
      : config_(config),
        pose_(start),
        rng_(seed),
        controller_(config.base, config.geometry, config.command_timeout) {}

  // Advances dt: reads commands from `bus` (the controller's side), moves, sends encoder
  // frames. A frozen body (after a collision) no longer moves.
  void step(TimePoint now, double dt, hal::CanBus& bus);
  void freeze() { frozen_ = true; }
  BaseEmulator& controller() { return controller_; }

  const Pose2& pose() const { return pose_; }
  double travelled_m() const { return travelled_; }
  double speed_mps() const { return 0.5 * (left_ + right_); }
  bool frozen() const { return frozen_; }
  const UgvBodyConfig& config() const { return config_; }

 private:
  UgvBodyConfig config_;
  Pose2 pose_;
  Rng rng_;
  double left_ = 0.0, right_ = 0.0;  // true wheel speeds
  double last_v_ = 0.0;              // the wheels' mean speed one step ago (for the slip)
  BaseEmulator controller_;
  double travelled_ = 0.0;
  bool frozen_ = false;
};

}  // namespace colag::sim
