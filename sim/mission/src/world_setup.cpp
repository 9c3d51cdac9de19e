#include "colag/sim/mission/world_setup.hpp"

#include <cmath>

#include "colag/common/random.hpp"

namespace colag::mission {

namespace {

// The world profile's camera.
sim::CameraConfig camera_of(const sim::CameraProfile& c) {
  sim::CameraConfig out;
  out.range_m = c.range_m;
  out.fov_half_angle_rad =
      c.fov_half_angle_deg >= 180.0 ? M_PI : c.fov_half_angle_deg * M_PI / 180.0;
  out.sigma_position_m = c.sigma_position_m;
  out.sigma_yaw_rad = c.sigma_yaw_rad;
  out.true_sigma_scale = c.true_sigma_scale;
  out.miss_probability = c.miss;
  out.outlier_probability = c.outlier;
  out.outlier_max_m = c.outlier_max_m;
  out.outlier_max_rad = c.outlier_max_deg * M_PI / 180.0;
  out.latency = seconds(c.latency_ms / 1e3);
  out.jitter = seconds(c.jitter_ms / 1e3);
  return out;
}

sim::UavOdometryErrors uav_odometry_of(const sim::UavOdometryProfile& o) {
  constexpr double kDeg = M_PI / 180.0;
  return {o.scale_error,   o.yaw_error_deg * kDeg, o.walk_m_per_sqrt_min / std::sqrt(60.0),
          o.jumps_per_min, o.jump_max_m,           seconds(o.latency_ms / 1e3)};
}

}  // namespace

sim::SimWorldConfig sim_world_config(const MissionConfig& cfg) {
  sim::SimWorldConfig wc;
  wc.seed = cfg.seed;
  wc.lidar.columns = cfg.lidar_columns;
  wc.ugv.encoder_bias = cfg.faults.odom_bias;
  wc.ugv.base.protocol = cfg.ugv_base;
  wc.camera = camera_of(cfg.world.camera);
  wc.lidar_errors = cfg.world.lidar;
  wc.uav.odometry = uav_odometry_of(cfg.world.uav_odometry);
  wc.uav.seed = cfg.seed * 104729ULL + 3;
  return wc;
}

std::vector<sim::WheelErrors> draw_wheels(const MissionConfig& cfg) {
  const sim::WheelProfile& w = cfg.world.wheels;
  std::vector<sim::WheelErrors> out(static_cast<std::size_t>(cfg.ugvs));
  Rng rng(cfg.seed * 0x2545F4914F6CDD1DULL + 0x3EE1);
  for (sim::WheelErrors& e : out) {
    e.left_scale = rng.uniform(-w.scale_spread, w.scale_spread);
    e.right_scale = rng.uniform(-w.scale_spread, w.scale_spread);
    e.yaw_rate_bias_radps = rng.uniform(-w.yaw_rate_bias_radps, w.yaw_rate_bias_radps);
    e.slip_per_radps = w.slip_per_radps;
    e.slip_per_mps2 = w.slip_per_mps2;
  }
  return out;
}

uav::LidarBeamPattern beam_pattern_of(const sim::LidarPattern& p) {
  return {p.beams, p.lowest_elevation_deg, p.elevation_step_deg, p.columns};
}

uav::CameraView camera_view_of(const sim::CameraConfig& c) {
  return {c.range_m, c.fov_half_angle_rad * 180.0 / M_PI, c.tag_height_m};
}

}  // namespace colag::mission
