#include "colag/uav/app/uav_config.hpp"

#include <numbers>

#include "colag/board/config.hpp"

namespace colag::uav {

namespace {
using board::child;

// The UAV's own sections; `doc` is const: const access never inserts keys.
void read_uav_sections(board::Reader& r, const YAML::Node& doc, UavBoardConfig& c) {
  const YAML::Node robot = child(doc, "robot");
  r.only(robot, "robot", {"id", "hal"});
  int id = 0;
  r.get(robot, "robot", "id", id, 0, 255);
  c.id = static_cast<RobotId>(id);
  std::string hal = "board";
  r.get(robot, "robot", "hal", hal);
  if (hal != "board" && hal != "sim") r.fail("robot.hal", "expected board or sim");
  c.sim_hal = hal == "sim";

  const YAML::Node cam = child(doc, "camera");
  r.only(
      cam, "camera",
      {"device", "calibration", "latency_ms", "tag_size_m", "decimate", "threads",
       "min_decision_margin", "max_range_m", "fov_half_angle_deg", "mount_xyz", "mount", "tags"});
  r.get(cam, "camera", "device", c.camera.uri);
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
  r.only(lidar, "lidar", {"beams", "lowest_elevation_deg", "elevation_step_deg", "columns"});
  LidarBeamPattern& p = c.lidar_pattern;
  p.beams = 0;
  r.get(lidar, "lidar", "beams", p.beams, 1, static_cast<int>(limits::kMaxLidarBeams));
  r.get(lidar, "lidar", "lowest_elevation_deg", p.lowest_elevation_deg, -90.0, 90.0);
  r.get(lidar, "lidar", "elevation_step_deg", p.elevation_step_deg, 0.01, 30.0);
  r.get(lidar, "lidar", "columns", p.columns, 1, static_cast<int>(limits::kMaxLidarColumns));
  if (r.ok() && lidar && p.beams == 0) r.require(lidar, "lidar", "beams");

  // The simulated camera needs no calibration.
  if (r.ok() && c.calibration_file.empty() && !c.sim_hal)
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

const board::ConfigSchema<UavBoardConfig> kSchema{{"robot", "camera", "lidar"}, read_uav_sections};
}  // namespace

bool load_uav_config(const std::string& path, UavBoardConfig& out, std::string& error) {
  return board::load_config(path, kSchema, out, error);
}

bool parse_uav_config(const std::string& text, const std::string& name, UavBoardConfig& out,
                      std::string& error) {
  return board::parse_config(text, name, kSchema, out, error);
}

}  // namespace colag::uav
