#include "colag/ugv/app/ugv_config.hpp"

#include "colag/board/config.hpp"

namespace colag::ugv {

namespace {
using board::child;

std::uint32_t can_id(board::Reader& r, const YAML::Node& can, const char* key, std::uint32_t id,
                     bool extended) {
  r.get(can, "can", key, id, 0u, extended ? 0x1FFFFFFFu : 0x7FFu);
  return id;
}

void read_colag_protocol(board::Reader& r, const YAML::Node& can,
                         hal::can::WheelProtocolConfig& p) {
  r.get(can, "can", "extended_ids", p.extended_ids);
  p.counts_id = can_id(r, can, "counts_id", p.counts_id, p.extended_ids);
  p.speeds_id = can_id(r, can, "speeds_id", p.speeds_id, p.extended_ids);
  p.command_id = can_id(r, can, "command_id", p.command_id, p.extended_ids);
  if (r.ok() &&
      (p.counts_id == p.speeds_id || p.counts_id == p.command_id || p.speeds_id == p.command_id))
    r.fail("can", "counts_id, speeds_id and command_id must differ");
}

void read_direction(board::Reader& r, const YAML::Node& n, const char* path, const char* key,
                    int& out) {
  r.get(n, path, key, out, -1, 1);
  if (out == 0) r.fail(std::string(path) + "." + key, "must be 1 or -1");
}

void read_odrive(board::Reader& r, const YAML::Node& n, hal::can::OdriveConfig& o) {
  const char* path = "can.odrive";
  r.only(n, path,
         {"left_node", "right_node", "left_direction", "right_direction", "gear_ratio",
          "clear_errors_at_start", "heartbeat_timeout_ms"});
  const auto max_node = static_cast<int>(hal::can::odrive::kMaxNodeId);
  int left = o.left.node, right = o.right.node;
  r.get(n, path, "left_node", left, 0, max_node);
  r.get(n, path, "right_node", right, 0, max_node);
  o.left.node = static_cast<std::uint8_t>(left);
  o.right.node = static_cast<std::uint8_t>(right);
  if (r.ok() && left == right) r.fail("can.odrive", "left_node and right_node must differ");
  read_direction(r, n, path, "left_direction", o.left.direction);
  read_direction(r, n, path, "right_direction", o.right.direction);
  r.get(n, path, "gear_ratio", o.motor_turns_per_wheel_turn, 0.01, 1000.0);
  r.get(n, path, "clear_errors_at_start", o.clear_errors_at_start);
  r.millis(n, path, "heartbeat_timeout_ms", o.heartbeat_timeout, 150.0, 5000.0);
}

void read_agilex(board::Reader& r, const YAML::Node& n, hal::can::AgilexConfig& a) {
  const char* path = "can.agilex";
  r.only(n, path,
         {"left_sign", "right_sign", "max_angular_radps", "clear_errors_at_start",
          "state_timeout_ms"});
  read_direction(r, n, path, "left_sign", a.left_sign);
  read_direction(r, n, path, "right_sign", a.right_sign);
  r.get(n, path, "max_angular_radps", a.max_angular_radps, 0.1, 10.0);
  r.get(n, path, "clear_errors_at_start", a.clear_errors_at_start);
  r.millis(n, path, "state_timeout_ms", a.state_timeout, 50.0, 5000.0);
}

// The UGV's own sections; `doc` is const: const access never inserts keys.
void read_ugv_sections(board::Reader& r, const YAML::Node& doc, UgvBoardConfig& c) {
  const YAML::Node robot = child(doc, "robot");
  r.only(robot, "robot",
         {"id", "goal", "via", "start_guess", "radius_m", "state_file", "state_max_age_s"});
  int id = 1;
  r.get(robot, "robot", "id", id, 0, static_cast<int>(limits::kMaxUgvs) - 1);
  c.nav.id = static_cast<RobotId>(id);
  double goal[2];
  if (r.vector(robot, "robot", "goal", goal, 2)) c.nav.goal = Vec2(goal[0], goal[1]);
  c.nav.via.clear();
  r.points(robot, "robot", "via", limits::kMaxRouteVias,
           [&](double x, double y) { (void)c.nav.via.push_back(Vec2(x, y)); });
  double start[3];
  if (r.vector(robot, "robot", "start_guess", start, 3)) {
    c.nav.has_start_guess = true;
    c.nav.start_guess = Pose2{Vec2(start[0], start[1]), start[2]};
  }
  r.get(robot, "robot", "radius_m", c.nav.body_radius_m, 0.05, 2.0);
  r.get(robot, "robot", "state_file", c.state_file);
  r.get(robot, "robot", "state_max_age_s", c.state_max_age_s, 1.0, 86400.0);

  const YAML::Node can = child(doc, "can");
  r.only(can, "can",
         {"interface", "protocol", "counts_id", "speeds_id", "command_id", "extended_ids", "odrive",
          "agilex"});
  r.get(can, "can", "interface", c.can_interface);
  if (r.ok() && c.can_interface.empty()) r.fail("can.interface", "must not be empty");
  std::string protocol = hal::can::to_string(c.base.protocol);
  r.get(can, "can", "protocol", protocol);
  if (!hal::can::parse_base_protocol(protocol, c.base.protocol))
    r.fail("can.protocol",
           "unknown protocol '" + protocol + "' (known: " + hal::can::kBaseProtocolNames + ")");
  // A section for another protocol than the one selected is a mistake worth naming.
  const bool colag = c.base.protocol == hal::can::BaseProtocol::kColag;
  for (const char* key : {"counts_id", "speeds_id", "command_id", "extended_ids"})
    if (!colag && child(can, key)) r.fail(std::string("can.") + key, "only with protocol colag");
  if (child(can, "odrive") && c.base.protocol != hal::can::BaseProtocol::kOdrive)
    r.fail("can.odrive", "only with protocol odrive");
  if (child(can, "agilex") && c.base.protocol != hal::can::BaseProtocol::kAgilexV2)
    r.fail("can.agilex", "only with protocol agilex_v2");
  read_colag_protocol(r, can, c.base.colag);
  read_odrive(r, child(can, "odrive"), c.base.odrive);
  read_agilex(r, child(can, "agilex"), c.base.agilex);

  const YAML::Node wheels = child(doc, "wheels");
  r.only(wheels, "wheels", {"radius_m", "track_m", "ticks_per_rev", "max_speed_mps"});
  r.get(wheels, "wheels", "radius_m", c.wheels.wheel_radius_m, 0.005, 1.0);
  r.get(wheels, "wheels", "track_m", c.wheels.track_width_m, 0.05, 5.0);
  r.get(wheels, "wheels", "ticks_per_rev", c.wheels.ticks_per_revolution, 1u, 1u << 20);
  r.get(wheels, "wheels", "max_speed_mps", c.wheels.max_wheel_speed_mps, 0.01, 10.0);

  const YAML::Node rates = child(doc, "rates");
  r.only(rates, "rates", {"control_hz", "planning_hz"});
  UgvSchedule& sched = c.nav.schedule;
  r.rate(rates, "rates", "control_hz", sched.control);
  r.rate(rates, "rates", "planning_hz", sched.planning);
  sched.transport = sched.transport.at_period(sched.control.period);  // polled every control tick

  const YAML::Node odo = child(doc, "odometry");
  r.only(odo, "odometry", {"timeout_ms", "sigma_v", "sigma_omega", "frame_walk", "calibration"});
  r.millis(odo, "odometry", "timeout_ms", c.nav.odometry_timeout, 10.0, 1000.0);
  // Zero would stop the estimate's uncertainty from growing: never true of wheels.
  r.get(odo, "odometry", "sigma_v", c.nav.ekf.noise.sigma_v_mps, 1e-4, 1.0);
  r.get(odo, "odometry", "sigma_omega", c.nav.ekf.noise.sigma_omega_radps, 1e-4, 1.0);
  r.get(odo, "odometry", "frame_walk", c.nav.ekf.frame_walk_m_per_sqrt_s, 0.0, 1.0);
  // What the wheel calibration may be off by (1 sigma): the estimator learns the rest.
  const YAML::Node cal = child(odo, "calibration");
  const std::string cp = "odometry.calibration";
  r.only(cal, cp,
         {"estimate", "scale", "turn_scale", "drift_per_m", "drift_per_s", "slip_per_radps",
          "turn_walk"});
  OdometryCalibrationModel& m = c.nav.ekf.calibration;
  r.get(cal, cp, "estimate", m.estimate);
  r.get(cal, cp, "scale", m.sigma_scale_v, 0.0, 0.3);
  r.get(cal, cp, "turn_scale", m.sigma_scale_omega, 0.0, 0.3);
  r.get(cal, cp, "drift_per_m", m.sigma_omega_per_m_radpm, 0.0, 0.5);
  r.get(cal, cp, "drift_per_s", m.sigma_omega_bias_radps, 0.0, 0.1);
  r.get(cal, cp, "slip_per_radps", m.sigma_slip_per_radps, 0.0, 0.5);
  r.get(cal, cp, "turn_walk", m.walk_turn_per_sqrt_rad, 0.0, 0.3);

  // Checked last, so that a wrong value elsewhere is the error reported first.
  r.require(robot, "robot", "id");
  r.require(robot, "robot", "goal");
}

const board::ConfigSchema<UgvBoardConfig> kSchema{{"robot", "can", "wheels", "rates", "odometry"},
                                                  read_ugv_sections};
}  // namespace

bool load_ugv_config(const std::string& path, UgvBoardConfig& out, std::string& error) {
  return board::load_config(path, kSchema, out, error);
}

bool parse_ugv_config(const std::string& text, const std::string& name, UgvBoardConfig& out,
                      std::string& error) {
  return board::parse_config(text, name, kSchema, out, error);
}

}  // namespace colag::ugv
