#include "colag/board/board_config.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <numbers>
#include <set>

namespace colag::board {

namespace {

// node[key] without yaml-cpp's surprises: absent (not null) when the node or the key is missing.
YAML::Node child(const YAML::Node& node, const char* key) {
  if (node && node.IsMap() && node[key]) return node[key];
  return YAML::Node(YAML::NodeType::Undefined);
}

// Walks a YAML document, reading typed values by key path and keeping the first error.
class Reader {
 public:
  Reader(const std::string& file, std::string& error) : file_(file), error_(error) {}

  bool ok() const { return error_.empty(); }
  void fail(const std::string& key, const std::string& problem) {
    if (ok()) error_ = file_ + ": " + key + ": " + problem;
  }

  // Checks that `node` (a map or absent) has only `allowed` keys.
  void only(const YAML::Node& node, const std::string& path, std::set<std::string> allowed) {
    if (!node) return;
    if (!node.IsMap()) return fail(path.empty() ? "(top level)" : path, "expected a mapping");
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (allowed.count(key) == 0) fail(join(path, key), "unknown key");
    }
  }

  template <class T>
  void get(const YAML::Node& node, const std::string& path, const char* key, T& out, T lo, T hi) {
    const YAML::Node v = child(node, key);
    if (!v) return;
    T value{};
    try {
      value = v.as<T>();
    } catch (const YAML::Exception&) {
      return fail(join(path, key), std::string("expected ") + kind<T>());
    }
    if (!(value >= lo && value <= hi)) {
      return fail(join(path, key), "out of range [" + show(lo) + ", " + show(hi) + "]");
    }
    out = value;
  }
  void get(const YAML::Node& node, const std::string& path, const char* key, std::string& out) {
    const YAML::Node v = child(node, key);
    if (!v) return;
    if (!v.IsScalar()) return fail(join(path, key), "expected a string");
    out = v.as<std::string>();
  }
  void get(const YAML::Node& node, const std::string& path, const char* key, bool& out) {
    const YAML::Node v = child(node, key);
    if (!v) return;
    try {
      out = v.as<bool>();
    } catch (const YAML::Exception&) {
      fail(join(path, key), "expected true or false");
    }
  }
  // A period given as a rate in Hz.
  void rate(const YAML::Node& node, const std::string& path, const char* key, Duration& out) {
    double hz = 0.0;
    bool present = node && node[key];
    get(node, path, key, hz, 0.1, 1000.0);
    if (present && ok()) out = std::chrono::nanoseconds(std::llround(1e9 / hz));
  }
  void millis(const YAML::Node& node, const std::string& path, const char* key, Duration& out,
              double lo, double hi) {
    double ms = std::chrono::duration<double, std::milli>(out).count();
    get(node, path, key, ms, lo, hi);
    out = std::chrono::nanoseconds(std::llround(ms * 1e6));
  }
  // [x, y] or [x, y, z] (n values).
  bool vector(const YAML::Node& node, const std::string& path, const char* key, double* out,
              std::size_t n) {
    const YAML::Node v = child(node, key);
    if (!v) return false;
    if (!v.IsSequence() || v.size() != n) {
      fail(join(path, key), "expected a list of " + std::to_string(n) + " numbers");
      return false;
    }
    for (std::size_t i = 0; i < n; ++i) {
      try {
        out[i] = v[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(join(path, key), "expected a list of " + std::to_string(n) + " numbers");
        return false;
      }
      if (!std::isfinite(out[i])) fail(join(path, key), "not finite");
    }
    return ok();
  }

 private:
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  template <class T>
  static const char* kind() {
    if constexpr (std::is_integral_v<T>) return "an integer";
    return "a number";
  }
  template <class T>
  static std::string show(T v) {
    if constexpr (std::is_floating_point_v<T>) {
      std::string s = std::to_string(v);
      s.erase(s.find_last_not_of('0') + 1);
      if (s.back() == '.') s.pop_back();
      return s;
    } else {
      return std::to_string(v);
    }
  }
  std::string file_;
  std::string& error_;
};

bool parse(const std::string& path, YAML::Node& root, std::string& error) {
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    error = path + ": cannot open the configuration file";
    return false;
  } catch (const YAML::Exception& e) {
    error = path + ": line " + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return false;
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // an empty file: all defaults
  return true;
}

void read_common(Reader& r, const YAML::Node& doc, CommonBoardConfig& c) {
  const YAML::Node dds = child(doc, "dds");
  r.only(dds, "dds", {"domain", "partition"});
  r.get(dds, "dds", "domain", c.dds_domain, 0u, 232u);  // DDS allows domain ids 0..232
  r.get(dds, "dds", "partition", c.dds_partition);
  const YAML::Node rt = child(doc, "realtime");
  r.only(rt, "realtime", {"fifo_priority", "lock_memory"});
  r.get(rt, "realtime", "fifo_priority", c.realtime.fifo_priority, 0, 99);
  r.get(rt, "realtime", "lock_memory", c.realtime.lock_memory);
}

std::uint32_t can_id(Reader& r, const YAML::Node& can, const char* key, std::uint32_t id,
                     bool extended) {
  r.get(can, "can", key, id, 0u, extended ? 0x1FFFFFFFu : 0x7FFu);
  return id;
}

}  // namespace

bool load_ugv_config(const std::string& path, UgvBoardConfig& out, std::string& error) {
  error.clear();
  YAML::Node root;
  if (!parse(path, root, error)) return false;
  Reader r(path, error);
  const YAML::Node& doc = root;  // const access never inserts keys
  UgvBoardConfig c;
  r.only(doc, "", {"robot", "dds", "realtime", "can", "wheels", "rates", "odometry"});
  const YAML::Node robot = child(doc, "robot");
  r.only(robot, "robot", {"id", "goal", "start_guess", "radius_m"});
  int id = 1;
  r.get(robot, "robot", "id", id, 1, static_cast<int>(limits::kMaxUgvs));
  c.nav.id = static_cast<RobotId>(id);
  double goal[2];
  if (r.vector(robot, "robot", "goal", goal, 2)) c.nav.goal = Vec2(goal[0], goal[1]);
  double start[3];
  if (r.vector(robot, "robot", "start_guess", start, 3)) {
    c.nav.has_start_guess = true;
    c.nav.start_guess = Pose2{Vec2(start[0], start[1]), start[2]};
  }
  r.get(robot, "robot", "radius_m", c.nav.body_radius_m, 0.05, 2.0);
  read_common(r, doc, c.common);

  const YAML::Node can = child(doc, "can");
  r.only(can, "can", {"interface", "counts_id", "speeds_id", "command_id", "extended_ids"});
  r.get(can, "can", "interface", c.can_interface);
  r.get(can, "can", "extended_ids", c.protocol.extended_ids);
  c.protocol.counts_id = can_id(r, can, "counts_id", c.protocol.counts_id, c.protocol.extended_ids);
  c.protocol.speeds_id = can_id(r, can, "speeds_id", c.protocol.speeds_id, c.protocol.extended_ids);
  c.protocol.command_id =
      can_id(r, can, "command_id", c.protocol.command_id, c.protocol.extended_ids);
  if (r.ok() && (c.protocol.counts_id == c.protocol.speeds_id ||
                 c.protocol.counts_id == c.protocol.command_id ||
                 c.protocol.speeds_id == c.protocol.command_id))
    r.fail("can", "counts_id, speeds_id and command_id must differ");
  if (r.ok() && c.can_interface.empty()) r.fail("can.interface", "must not be empty");

  const YAML::Node wheels = child(doc, "wheels");
  r.only(wheels, "wheels", {"radius_m", "track_m", "ticks_per_rev", "max_speed_mps"});
  r.get(wheels, "wheels", "radius_m", c.wheels.wheel_radius_m, 0.005, 1.0);
  r.get(wheels, "wheels", "track_m", c.wheels.track_width_m, 0.05, 5.0);
  r.get(wheels, "wheels", "ticks_per_rev", c.wheels.ticks_per_revolution, 1u, 1u << 20);
  r.get(wheels, "wheels", "max_speed_mps", c.wheels.max_wheel_speed_mps, 0.01, 10.0);

  const YAML::Node rates = child(doc, "rates");
  r.only(rates, "rates", {"control_hz", "planning_hz"});
  r.rate(rates, "rates", "control_hz", c.control_period);
  r.rate(rates, "rates", "planning_hz", c.planning_period);

  const YAML::Node odo = child(doc, "odometry");
  r.only(odo, "odometry", {"timeout_ms", "sigma_v", "sigma_omega"});
  r.millis(odo, "odometry", "timeout_ms", c.nav.odometry_timeout, 10.0, 1000.0);
  r.get(odo, "odometry", "sigma_v", c.nav.ekf.noise.sigma_v_mps, 0.0, 1.0);
  r.get(odo, "odometry", "sigma_omega", c.nav.ekf.noise.sigma_omega_radps, 0.0, 1.0);
  if (!r.ok()) return false;
  out = c;
  return true;
}

bool load_uav_config(const std::string& path, UavBoardConfig& out, std::string& error) {
  error.clear();
  YAML::Node root;
  if (!parse(path, root, error)) return false;
  Reader r(path, error);
  const YAML::Node& doc = root;
  UavBoardConfig c;
  r.only(doc, "", {"robot", "dds", "realtime", "camera"});
  const YAML::Node robot = child(doc, "robot");
  r.only(robot, "robot", {"id"});
  int id = 0;
  r.get(robot, "robot", "id", id, 0, 255);
  c.id = static_cast<RobotId>(id);
  read_common(r, doc, c.common);

  const YAML::Node cam = child(doc, "camera");
  r.only(cam, "camera",
         {"device", "calibration", "latency_ms", "tag_size_m", "decimate", "threads",
          "min_decision_margin", "max_range_m", "mount_xyz", "mount", "tags"});
  r.get(cam, "camera", "device", c.camera.uri);
  r.get(cam, "camera", "calibration", c.calibration_file);
  r.millis(cam, "camera", "latency_ms", c.camera.latency, 0.0, 1000.0);
  r.get(cam, "camera", "tag_size_m", c.rpe.tag_size_m, 0.01, 2.0);
  r.get(cam, "camera", "decimate", c.rpe.decimate, 1.0f, 8.0f);
  r.get(cam, "camera", "threads", c.rpe.threads, 1, 8);
  r.get(cam, "camera", "min_decision_margin", c.rpe.min_decision_margin, 0.0, 255.0);
  r.get(cam, "camera", "max_range_m", c.rpe.max_range_m, 0.1, 50.0);
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
      r.get(tags[i], p, "ugv", ugv, 1, static_cast<int>(limits::kMaxUgvs));
      r.get(tags[i], p, "height_m", height, 0.0, 3.0);
      if (r.ok() && (tag < 0 || ugv < 0)) r.fail(p, "needs both tag and ugv");
      // A tag lying flat on top of the UGV, its x along the UGV's x, facing up.
      const Pose3 on_top{Vec3(0, 0, height),
                         Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitX()))};
      if (r.ok() && !c.rpe.tags.push_back({tag, static_cast<RobotId>(ugv), on_top}))
        r.fail("camera.tags", "too many tags");
    }
  }
  if (r.ok() && c.calibration_file.empty())
    r.fail("camera.calibration", "required (an OpenCV calibration YAML)");
  if (r.ok()) {
    // Relative to the configuration file.
    std::string file = c.calibration_file;
    if (!file.empty() && file[0] != '/') {
      const auto slash = path.find_last_of('/');
      if (slash != std::string::npos) file = path.substr(0, slash + 1) + file;
    }
    std::string cal_error;
    if (!linux_hal::load_intrinsics(file, c.rpe.camera, cal_error))
      r.fail("camera.calibration", cal_error);
    c.calibration_file = file;
  }
  if (!r.ok()) return false;
  out = c;
  return true;
}

}  // namespace colag::board
