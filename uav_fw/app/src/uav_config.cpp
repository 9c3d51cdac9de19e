#include "colag/uav/app/uav_config.hpp"

#include <numbers>

#include "colag/board/config.hpp"

namespace colag::uav {

namespace {
using board::child;

// The UAV's own sections; `doc` is const: const access never inserts keys.
// [x, y, z, yaw_deg] or [x, y, z, roll_deg, pitch_deg, yaw_deg] (a pose in a parent frame).
bool read_pose(board::Reader& r, const YAML::Node& node, const std::string& path, const char* key,
               Pose3& out, bool full) {
  double v[6] = {0, 0, 0, 0, 0, 0};
  if (!r.vector(node, path, key, v, full ? 6 : 4)) return false;
  const double d = std::numbers::pi / 180.0;
  const double roll = full ? v[3] : 0.0, pitch = full ? v[4] : 0.0, yaw = full ? v[5] : v[3];
  out.p = Vec3(v[0], v[1], v[2]);
  out.q =
      Quat(Eigen::AngleAxisd(yaw * d, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch * d, Vec3::UnitY()) *
           Eigen::AngleAxisd(roll * d, Vec3::UnitX()));
  return true;
}

// robot.hal px4: PX4, the odometry and the LiDAR, each a DDS participant of its own.
void read_flight_stack(board::Reader& r, const YAML::Node& doc, UavBoardConfig& c) {
  const YAML::Node px4 = child(doc, "px4");
  r.only(px4, "px4",
         {"release", "dds_domain", "namespace", "system_id", "origin", "silence_timeout_ms",
          "status_timeout_ms"});
  if (c.px4_hal && !px4) r.fail("px4", "required with robot.hal px4 (at least px4.release)");
  hal::px4::Px4DriverConfig& p = c.px4;
  std::string release;
  r.get(px4, "px4", "release", release);
  if (r.ok() && px4) {
    if (release.empty()) {
      r.fail("px4.release", "required: the PX4 release on the aircraft (" +
                                std::string(hal::px4::kKnownPx4Releases) + ")");
    } else if (const auto rel = hal::px4::parse_px4_release(release); !rel) {
      r.fail("px4.release", "'" + release + "' is not a known release (" +
                                std::string(hal::px4::kKnownPx4Releases) + ")");
    } else {
      p.release = rel.value();
    }
  }
  int system = 1;
  r.get(px4, "px4", "dds_domain", p.dds_domain, 0u, 232u);  // DDS allows domain ids 0..232
  r.get(px4, "px4", "namespace", p.ns);
  r.get(px4, "px4", "system_id", system, 1, 255);
  p.target_system = static_cast<std::uint8_t>(system);
  (void)read_pose(r, px4, "px4", "origin", p.origin, false);
  r.millis(px4, "px4", "silence_timeout_ms", p.offboard.silence_timeout, 100.0, 900.0);
  r.millis(px4, "px4", "status_timeout_ms", p.offboard.status_timeout, 200.0, 5000.0);

  const YAML::Node odom = child(doc, "odometry");
  r.only(odom, "odometry",
         {"source", "topic", "dds_domain", "origin", "body_to_uav", "latency_ms"});
  std::string source = "fast_lio";
  r.get(odom, "odometry", "source", source);
  if (source != "fast_lio" && source != "px4")
    r.fail("odometry.source", "expected fast_lio (nav_msgs/Odometry) or px4 (VehicleOdometry)");
  c.odometry_from_px4 = source == "px4";
  hal::ros2::Ros2OdometryConfig& o = c.odometry;
  o.dds_domain = p.dds_domain;  // PX4's agent's unless said
  r.get(odom, "odometry", "dds_domain", o.dds_domain, 0u, 232u);
  r.get(odom, "odometry", "topic", o.topic);
  (void)read_pose(r, odom, "odometry", "origin", o.origin, false);
  (void)read_pose(r, odom, "odometry", "body_to_uav", o.body_to_uav, true);
  r.millis(odom, "odometry", "latency_ms", o.latency, 0.0, 500.0);
  if (c.odometry_from_px4) p.odometry_latency = o.latency;

  const YAML::Node lidar = child(doc, "lidar");
  hal::ros2::Ros2LidarConfig& l = c.lidar;
  l.dds_domain = p.dds_domain;
  r.get(lidar, "lidar", "dds_domain", l.dds_domain, 0u, 232u);
  r.get(lidar, "lidar", "topic", l.topic);
  (void)read_pose(r, lidar, "lidar", "mount", c.lidar_mount, true);
  r.get(lidar, "lidar", "min_range_m", l.min_range_m, 0.0F, 5.0F);
  r.get(lidar, "lidar", "max_range_m", l.max_range_m, 1.0F, 100.0F);
  r.millis(lidar, "lidar", "latency_ms", l.latency, 0.0, 500.0);
  if (r.ok() && l.min_range_m >= l.max_range_m)
    r.fail("lidar.min_range_m", "must be below lidar.max_range_m");
  if (r.ok() && (l.topic.empty() || o.topic.empty()))
    r.fail(l.topic.empty() ? "lidar.topic" : "odometry.topic", "empty");
}

void read_uav_sections(board::Reader& r, const YAML::Node& doc, UavBoardConfig& c) {
  const YAML::Node robot = child(doc, "robot");
  r.only(robot, "robot", {"id", "hal"});
  int id = 0;
  // The UGVs and the other UAVs refuse a UAV id beyond the fleet's (limits::kMaxUavs).
  r.get(robot, "robot", "id", id, 0, static_cast<int>(limits::kMaxUavs) - 1);
  c.id = static_cast<RobotId>(id);
  std::string hal = "board";
  r.get(robot, "robot", "hal", hal);
  if (hal != "board" && hal != "sim" && hal != "px4")
    r.fail("robot.hal", "expected board, sim or px4");
  c.sim_hal = hal == "sim";
  c.px4_hal = hal == "px4";
  read_flight_stack(r, doc, c);

  const YAML::Node fleet = child(doc, "fleet");
  r.only(fleet, "fleet", {"separation_m", "peer_timeout_ms", "peer_failsafe_ms"});
  r.get(fleet, "fleet", "separation_m", c.separation_m, 0.3, 20.0);
  r.millis(fleet, "fleet", "peer_timeout_ms", c.peer_timeout, 200.0, 30000.0);
  r.millis(fleet, "fleet", "peer_failsafe_ms", c.peer_failsafe, 0.0, 10000.0);

  const YAML::Node cam = child(doc, "camera");
  r.only(
      cam, "camera",
      {"device", "calibration", "latency_ms", "tag_size_m", "decimate", "threads",
       "min_decision_margin", "max_range_m", "fov_half_angle_deg", "mount_xyz", "mount", "tags"});
  r.get(cam, "camera", "device", c.camera.uri);
  c.sim_camera = c.camera.uri == "sim";
  r.get(cam, "camera", "calibration", c.calibration_file);
  r.millis(cam, "camera", "latency_ms", c.camera.latency, 0.0, 1000.0);
  r.get(cam, "camera", "tag_size_m", c.rpe.tag_size_m, 0.01, 2.0);
  r.get(cam, "camera", "decimate", c.rpe.decimate, 1.0f, 8.0f);
  r.get(cam, "camera", "threads", c.rpe.threads, 1, 8);
  r.get(cam, "camera", "min_decision_margin", c.rpe.min_decision_margin, 0.0, 255.0);
  r.get(cam, "camera", "max_range_m", c.rpe.max_range_m, 0.1, 50.0);
  // Its view, for the altitude: not set, the cone inscribed in the calibrated image of a
  // downward camera; otherwise (no calibration: the simulated camera; a forward camera) 180: it
  // is flown at the flight layer's altitude.
  double fov = 0.0;
  r.get(cam, "camera", "fov_half_angle_deg", fov, 1.0, 180.0);
  std::string mount = "downward";
  r.get(cam, "camera", "mount", mount);
  double xyz[3] = {0, 0, 0};
  (void)r.vector(cam, "camera", "mount_xyz", xyz, 3);
  if (mount == "downward") {
    c.rpe.camera_in_uav = linux_hal::downward_camera_mount(Vec3(xyz[0], xyz[1], xyz[2]));
  } else if (mount == "forward") {  // optical z = body x, optical x = body -y
    Mat3 rot;
    rot.col(0) = -Vec3::UnitY();
    rot.col(1) = -Vec3::UnitZ();
    rot.col(2) = Vec3::UnitX();
    c.rpe.camera_in_uav = Pose3{Vec3(xyz[0], xyz[1], xyz[2]), Quat(rot)};
  } else {
    r.fail("camera.mount", "expected downward or forward");
  }
  const YAML::Node tags = child(cam, "tags");
  if (tags && !tags.IsSequence()) r.fail("camera.tags", "expected a list of {tag, ugv, height_m}");
  if (tags && tags.IsSequence()) {
    for (std::size_t i = 0; i < tags.size() && r.ok(); ++i) {
      const std::string p = "camera.tags[" + std::to_string(i) + "]";
      r.only(tags[i], p, {"tag", "ugv", "height_m"});
      int tag = -1, ugv = -1;
      double height = 0.3;
      r.get(tags[i], p, "tag", tag, 0, 586);  // tag36h11 has 587 codes
      r.get(tags[i], p, "ugv", ugv, 0, static_cast<int>(limits::kMaxUgvs) - 1);
      r.get(tags[i], p, "height_m", height, 0.0, 3.0);
      if (r.ok() && (tag < 0 || ugv < 0)) r.fail(p, "needs both tag and ugv");
      // A tag lying flat on top of the UGV, its x along the UGV's x, facing up.
      const Pose3 on_top{Vec3(0, 0, height),
                         Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitX()))};
      if (r.ok() && !c.rpe.tags.push_back({tag, static_cast<RobotId>(ugv), on_top}))
        r.fail("camera.tags", "too many tags");
    }
  }
  // The LiDAR's beams (a spinning LiDAR's pattern; not set: nothing is inferred of the beams
  // without a return, and the UAV flies at the flight layer's altitude).
  const YAML::Node lidar = child(doc, "lidar");
  r.only(lidar, "lidar",
         {"beams", "lowest_elevation_deg", "elevation_step_deg", "columns", "topic", "dds_domain",
          "mount", "min_range_m", "max_range_m", "latency_ms"});
  LidarBeamPattern& p = c.lidar_pattern;
  p.beams = 0;
  r.get(lidar, "lidar", "beams", p.beams, 1, static_cast<int>(limits::kMaxLidarBeams));
  r.get(lidar, "lidar", "lowest_elevation_deg", p.lowest_elevation_deg, -90.0, 90.0);
  r.get(lidar, "lidar", "elevation_step_deg", p.elevation_step_deg, 0.01, 30.0);
  r.get(lidar, "lidar", "columns", p.columns, 1, static_cast<int>(limits::kMaxLidarColumns));
  // The pattern is all or nothing: a Livox Mid-360's is non-repetitive (returns only).
  const bool pattern = child(lidar, "lowest_elevation_deg") || child(lidar, "elevation_step_deg") ||
                       child(lidar, "columns");
  if (r.ok() && pattern && p.beams == 0) r.require(lidar, "lidar", "beams");

  // The simulated camera needs no calibration.
  if (r.ok() && c.calibration_file.empty() && !c.sim_hal && !c.sim_camera)
    r.fail("camera.calibration", "required (an OpenCV calibration YAML)");
  if (r.ok() && !c.calibration_file.empty()) {
    const std::string file = board::relative_to(r.file(), c.calibration_file);
    std::string cal_error;
    if (!linux_hal::load_intrinsics(file, c.rpe.camera, cal_error))
      r.fail("camera.calibration", cal_error);
    c.calibration_file = file;
  }
  if (r.ok() && fov == 0.0) {
    const linux_hal::CameraIntrinsics& k = c.rpe.camera;
    fov = c.calibration_file.empty() || mount != "downward" || !(k.fx > 0.0 && k.fy > 0.0)
              ? 180.0
              : std::atan(std::min(0.5 * k.width / k.fx, 0.5 * k.height / k.fy)) * 180.0 / M_PI;
  }
  double tag_height = CameraView{}.tag_height_m;  // the tags' mean height above the UGVs' origins
  if (!c.rpe.tags.empty()) {
    tag_height = 0.0;
    for (const auto& t : c.rpe.tags)
      tag_height += t.tag_in_body.p.z() / static_cast<double>(c.rpe.tags.size());
  }
  c.camera_view = {c.rpe.max_range_m, fov, tag_height};
  r.require(robot, "robot", "id");  // checked last: a wrong value elsewhere is reported first
}

const board::ConfigSchema<UavBoardConfig> kSchema{
    {"robot", "fleet", "camera", "lidar", "px4", "odometry"}, read_uav_sections};
}  // namespace

bool load_uav_config(const std::string& path, UavBoardConfig& out, std::string& error) {
  return board::load_config(path, kSchema, out, error);
}

bool parse_uav_config(const std::string& text, const std::string& name, UavBoardConfig& out,
                      std::string& error) {
  return board::parse_config(text, name, kSchema, out, error);
}

}  // namespace colag::uav
