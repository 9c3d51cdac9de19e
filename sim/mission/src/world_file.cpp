#include "colag/sim/mission/world_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

#include "colag/board/yaml_reader.hpp"

namespace colag::mission {

bool load_world_file(const std::string& file, sim::WorldProfile& out, std::string& error) {
  YAML::Node root;
  if (!board::load_yaml_file(file, root, error)) return false;
  board::Reader r(file, error);
  r.only(root, "", {"base", "wheels", "lidar", "camera", "uav_odometry", "clocks"});
  std::string base = "field";
  r.get(root, "", "base", base);
  if (!r.ok()) return false;
  sim::WorldProfile w;
  if (base == "field") {
    w = sim::field_world();
  } else if (base != "ideal") {
    r.fail("base", "expected ideal or field");
    return false;
  }
  w.name = file;
  const YAML::Node wheels = board::child(root, "wheels");
  r.only(wheels, "wheels",
         {"scale_spread", "slip_per_radps", "slip_per_mps2", "yaw_rate_bias_radps"});
  r.get(wheels, "wheels", "scale_spread", w.wheels.scale_spread, 0.0, 0.3);
  r.get(wheels, "wheels", "slip_per_radps", w.wheels.slip_per_radps, 0.0, 1.0);
  r.get(wheels, "wheels", "slip_per_mps2", w.wheels.slip_per_mps2, 0.0, 1.0);
  r.get(wheels, "wheels", "yaw_rate_bias_radps", w.wheels.yaw_rate_bias_radps, 0.0, 0.5);
  const YAML::Node lidar = board::child(root, "lidar");
  r.only(lidar, "lidar", {"range_sigma_m", "dropout", "returns_only"});
  r.get(lidar, "lidar", "range_sigma_m", w.lidar.range_sigma_m, 0.0, 0.5);
  r.get(lidar, "lidar", "dropout", w.lidar.dropout, 0.0, 0.9);
  r.get(lidar, "lidar", "returns_only", w.lidar.returns_only);
  const YAML::Node cam = board::child(root, "camera");
  r.only(cam, "camera",
         {"range_m", "fov_half_angle_deg", "sigma_position_m", "sigma_yaw_deg", "true_sigma_scale",
          "miss", "outlier", "outlier_max_m", "outlier_max_deg", "latency_ms", "jitter_ms"});
  sim::CameraProfile& c = w.camera;
  r.get(cam, "camera", "range_m", c.range_m, 0.5, 50.0);
  r.get(cam, "camera", "fov_half_angle_deg", c.fov_half_angle_deg, 5.0, 180.0);
  r.get(cam, "camera", "sigma_position_m", c.sigma_position_m, 0.001, 2.0);
  double sigma_yaw_deg = c.sigma_yaw_rad * 180.0 / M_PI;
  const bool yaw_given = static_cast<bool>(board::child(cam, "sigma_yaw_deg"));
  r.get(cam, "camera", "sigma_yaw_deg", sigma_yaw_deg, 0.01, 45.0);
  if (yaw_given) c.sigma_yaw_rad = sigma_yaw_deg * M_PI / 180.0;
  r.get(cam, "camera", "true_sigma_scale", c.true_sigma_scale, 0.1, 10.0);
  r.get(cam, "camera", "miss", c.miss, 0.0, 0.99);
  r.get(cam, "camera", "outlier", c.outlier, 0.0, 0.5);
  r.get(cam, "camera", "outlier_max_m", c.outlier_max_m, 0.0, 10.0);
  r.get(cam, "camera", "outlier_max_deg", c.outlier_max_deg, 0.0, 180.0);
  r.get(cam, "camera", "latency_ms", c.latency_ms, 0.0, 1000.0);
  r.get(cam, "camera", "jitter_ms", c.jitter_ms, 0.0, 1000.0);
  const YAML::Node odo = board::child(root, "uav_odometry");
  const std::string op = "uav_odometry";
  r.only(odo, op,
         {"scale_error", "yaw_error_deg", "walk_m_per_sqrt_min", "jumps_per_min", "jump_max_m",
          "latency_ms"});
  sim::UavOdometryProfile& o = w.uav_odometry;
  r.get(odo, op, "scale_error", o.scale_error, 0.0, 0.2);
  r.get(odo, op, "yaw_error_deg", o.yaw_error_deg, 0.0, 30.0);
  r.get(odo, op, "walk_m_per_sqrt_min", o.walk_m_per_sqrt_min, 0.0, 10.0);
  r.get(odo, op, "jumps_per_min", o.jumps_per_min, 0.0, 60.0);
  r.get(odo, op, "jump_max_m", o.jump_max_m, 0.0, 5.0);
  // Up to what the simulated odometry can hold in flight (64 world steps of 20 ms).
  r.get(odo, op, "latency_ms", o.latency_ms, 0.0, 500.0);
  const YAML::Node clocks = board::child(root, "clocks");
  r.only(clocks, "clocks", {"offset_s", "drift_ppm"});
  r.get(clocks, "clocks", "offset_s", w.clocks.offset_s, 0.0, 1e6);
  r.get(clocks, "clocks", "drift_ppm", w.clocks.drift_ppm, 0.0, 1000.0);
  if (!r.ok()) return false;
  out = w;
  return true;
}

bool world_from_name(const std::string& name, sim::WorldProfile& out, std::string& error) {
  if (name == "ideal") {
    out = sim::ideal_world();
    return true;
  }
  if (name == "field") {
    out = sim::field_world();
    return true;
  }
  if (!std::filesystem::exists(name)) {
    error = "'" + name + "' is neither ideal, field nor a world-profile YAML file";
    return false;
  }
  return load_world_file(name, out, error);
}

}  // namespace colag::mission
