#include "colag/sim/world/world_profile.hpp"

namespace colag::sim {

WorldProfile ideal_world() {
  return {};
}

// The numbers, and where they come from, are in config/worlds/field.yaml (the same values).
WorldProfile field_world() {
  WorldProfile w;
  w.name = "field";
  w.wheels.scale_spread = 0.05;
  w.wheels.slip_per_radps = 0.10;
  w.wheels.slip_per_mps2 = 0.05;
  w.wheels.yaw_rate_bias_radps = 0.01;
  w.lidar.range_sigma_m = 0.02;
  w.lidar.dropout = 0.05;
  w.lidar.returns_only = true;
  w.camera.fov_half_angle_deg = 75.0;
  w.camera.true_sigma_scale = 1.5;
  w.camera.miss = 0.10;
  w.camera.outlier = 0.02;
  w.camera.outlier_max_m = 1.0;
  w.camera.outlier_max_deg = 30.0;
  w.camera.latency_ms = 60.0;
  w.camera.jitter_ms = 30.0;
  w.uav_odometry.scale_error = 0.005;
  w.uav_odometry.yaw_error_deg = 0.3;
  w.uav_odometry.walk_m_per_sqrt_min = 0.02;
  w.uav_odometry.jumps_per_min = 0.5;
  w.uav_odometry.jump_max_m = 0.10;
  w.uav_odometry.latency_ms = 20.0;
  w.clocks.offset_s = 10.0;
  w.clocks.drift_ppm = 30.0;
  return w;
}

}  // namespace colag::sim
