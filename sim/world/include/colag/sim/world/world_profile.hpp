#pragma once
// How unkind the simulated world is: the `ideal` world gives the firmware exactly the noise its
// models assume (the paper's simulation, for reproducing its tables); the `field` world what
// real wheels, cameras, LiDARs and clocks do. Every parameter can be set in a YAML scenario file
// (config/worlds/field.yaml documents each, with where its default comes from). Per-robot values
// (each UGV's wheels, each clock) are drawn from the profile with the mission's seed.
#include <string>

#include "colag/common/time.hpp"
#include "colag/sim/world/lidar_errors.hpp"

namespace colag::sim {

struct WheelProfile {
  double scale_spread = 0.0;         // each encoder's scale error: uniform in +-this
  double slip_per_radps = 0.0;       // turn-rate slip (skid steering), see WheelErrors
  double slip_per_mps2 = 0.0;        // acceleration slip
  double yaw_rate_bias_radps = 0.0;  // each UGV's: uniform in +-this
};

struct CameraProfile {
  double range_m = 5.0;
  double fov_half_angle_deg = 180.0;  // from straight down; 180 = every direction (the paper's)
  double sigma_position_m = 0.2;      // what it reports
  double sigma_yaw_rad = 0.05;        // what it reports (the YAML file: sigma_yaw_deg)
  double true_sigma_scale = 1.0;      // its true error sigma = this x what it reports
  double miss = 0.0;                  // share of visible tags not detected
  double outlier = 0.0;               // share of detections far off
  double outlier_max_m = 1.0;
  double outlier_max_deg = 30.0;
  double latency_ms = 0.0;  // capture to delivery
  double jitter_ms = 0.0;   // + uniform 0..jitter
};

// The UAV's odometry, as a LiDAR-inertial odometry gives it (see UavOdometryErrors).
struct UavOdometryProfile {
  double scale_error = 0.0;
  double yaw_error_deg = 0.0;
  double walk_m_per_sqrt_min = 0.0;
  double jumps_per_min = 0.0;
  double jump_max_m = 0.0;
  double latency_ms = 0.0;
};

struct ClockProfile {
  double offset_s = 0.0;   // each UGV's clock within +-this of the UAV's
  double drift_ppm = 0.0;  // each crystal within +-this
};

struct WorldProfile {
  std::string name = "ideal";
  WheelProfile wheels;
  LidarErrors lidar;  // what SimWorld adds to each scan
  CameraProfile camera;
  UavOdometryProfile uav_odometry;
  ClockProfile clocks;
};

WorldProfile ideal_world();
WorldProfile field_world();

}  // namespace colag::sim
