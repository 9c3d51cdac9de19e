#include "colag/hal/ros2/ros2_messages.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace colag::hal::ros2 {

namespace {

char* c_str(const char* s) {
  return const_cast<char*>(s);  // NOLINT(cppcoreguidelines-pro-type-const-cast): read-only on write
}
char* c_str(Name& n) {
  return n.data();
}
char kEmpty[] = "";

void set_header(std_msgs_msg_dds__Header_& h, Name& frame, TimePoint stamp) {
  set_time(h.stamp, stamp);
  h.frame_id = c_str(frame);
}

// Every string of a marker must point somewhere: the unused ones at "".
void blank(visualization_msgs_msg_dds__Marker_& m) {
  m = {};
  m.ns = kEmpty;
  m.texture_resource = kEmpty;
  m.texture.header.frame_id = kEmpty;
  m.texture.format = kEmpty;
  m.text = kEmpty;
  m.mesh_resource = kEmpty;
  m.mesh_file.filename = kEmpty;
}

}  // namespace

void set_name(Name& out, std::string_view text) {
  const std::size_t n = std::min(text.size(), out.size() - 1);
  std::memcpy(out.data(), text.data(), n);
  out[n] = '\0';
}

void set_time(builtin_interfaces_msg_dds__Time_& out, TimePoint stamp) {
  const std::int64_t ns = std::max<std::int64_t>(0, stamp.time_since_epoch().count());
  out.sec = static_cast<std::int32_t>(ns / 1'000'000'000);
  out.nanosec = static_cast<std::uint32_t>(ns % 1'000'000'000);
}

void set_yaw(geometry_msgs_msg_dds__Quaternion_& out, double yaw_rad) {
  out = {0.0, 0.0, std::sin(yaw_rad / 2.0), std::cos(yaw_rad / 2.0)};
}

void set_pose(geometry_msgs_msg_dds__Pose_& out, double x, double y, double z, double yaw_rad) {
  out.position = {x, y, z};
  set_yaw(out.orientation, yaw_rad);
}

std::string base_link(std::string_view ns) {
  std::string out(ns);
  if (!out.empty() && out.back() != '/') out += '/';
  return out + "base_link";
}

OdometryMessage::OdometryMessage(std::string_view child_frame) {
  set_name(frame_, kMapFrame);
  set_name(child_, child_frame);
  msg_.header.frame_id = c_str(frame_);
  msg_.child_frame_id = c_str(child_);
}

void OdometryMessage::set(const msg::UgvStatus& s) {
  set_time(msg_.header.stamp, s.stamp);
  set_pose(msg_.pose.pose, s.position_m[0], s.position_m[1], 0.0, s.yaw_rad);
  // (x, y, yaw) -> the 6x6 of (x, y, z, rx, ry, rz); the unobserved axes get a large variance.
  double* c = msg_.pose.covariance;
  std::fill(c, c + 36, 0.0);
  const int map[3] = {0, 1, 5};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      c[map[r] * 6 + map[k]] = s.covariance[r * 3 + k];
  c[2 * 6 + 2] = c[3 * 6 + 3] = c[4 * 6 + 4] = 1e6;
  msg_.twist.twist.linear = {s.velocity_mps, 0.0, 0.0};
  msg_.twist.twist.angular = {0.0, 0.0, s.yaw_rate_radps};
  std::fill(msg_.twist.covariance, msg_.twist.covariance + 36, 0.0);
  msg_.twist.covariance[0] = -1.0;  // commanded, not estimated: unknown
}

void OdometryMessage::set(const msg::UavOdometry& o) {
  set_time(msg_.header.stamp, o.stamp);
  msg_.pose.pose.position = {o.position_m[0], o.position_m[1], o.position_m[2]};
  msg_.pose.pose.orientation = {o.orientation_wxyz[1], o.orientation_wxyz[2], o.orientation_wxyz[3],
                                o.orientation_wxyz[0]};
  std::fill(msg_.pose.covariance, msg_.pose.covariance + 36, 0.0);
  msg_.pose.covariance[0] = -1.0;
  // The world-frame velocity into the body frame (REP-105: twist in child_frame_id).
  const double w = o.orientation_wxyz[0], x = o.orientation_wxyz[1], y = o.orientation_wxyz[2],
               z = o.orientation_wxyz[3];
  const double* v = o.velocity_mps;
  // R^T v for the rotation of (w, x, y, z).
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  msg_.twist.twist.linear = {r[0][0] * v[0] + r[1][0] * v[1] + r[2][0] * v[2],
                             r[0][1] * v[0] + r[1][1] * v[1] + r[2][1] * v[2],
                             r[0][2] * v[0] + r[1][2] * v[1] + r[2][2] * v[2]};
  msg_.twist.twist.angular = {0.0, 0.0, o.yaw_rate_radps};
  std::fill(msg_.twist.covariance, msg_.twist.covariance + 36, 0.0);
  msg_.twist.covariance[0] = -1.0;
}

UgvStatusMessage::UgvStatusMessage() {
  set_name(frame_, kMapFrame);
  msg_.header.frame_id = c_str(frame_);
  msg_.mode_name = msg_.blocked_reason_text = msg_.base_fault_text = msg_.last_goal_text =
      msg_.last_command_text = kEmpty;
}

void UgvStatusMessage::set_commands(std::uint32_t received, std::uint32_t last_id,
                                    std::uint8_t last, std::uint8_t last_result, const char* text) {
  msg_.commands_received = received;
  msg_.last_command_id = last_id;
  msg_.last_command = last;
  msg_.last_command_result = last_result;
  msg_.last_command_text = c_str(received == 0 ? "" : text);
}

void UgvStatusMessage::set_goals(std::uint32_t received, std::uint8_t last_result,
                                 const char* text) {
  msg_.goals_received = received;
  msg_.last_goal_result = last_result;
  msg_.last_goal_text = c_str(received == 0 ? "" : text);
}

void UgvStatusMessage::set(const msg::UgvStatus& s) {
  set_time(msg_.header.stamp, s.stamp);
  msg_.ugv_id = s.ugv_id;
  msg_.mode = static_cast<std::uint8_t>(s.mode);
  msg_.mode_name = c_str(msg::to_string(s.mode));
  msg_.blocked_reason = static_cast<std::uint8_t>(s.blocked_reason);
  msg_.blocked_reason_text = c_str(msg::to_string(s.blocked_reason));
  msg_.base_fault = static_cast<std::uint8_t>(s.base_fault);
  msg_.base_fault_text = c_str(msg::to_string(s.base_fault));
  msg_.base_error = s.base_error;
  msg_.goal = {s.goal_m[0], s.goal_m[1], 0.0};
  msg_.waiting_time_s = s.waiting_time_s;
  msg_.clock_error_s = s.clock_error_s;
  msg_.rejected_inputs = s.rejected_inputs;
  msg_.overruns = s.overruns;
  msg_.degradation = s.degradation;
}

UavStatusMessage::UavStatusMessage() {
  set_name(frame_, kMapFrame);
  msg_.header.frame_id = c_str(frame_);
  msg_.flight_name = msg_.fault_text = kEmpty;
}

void UavStatusMessage::set(const msg::UavOdometry& o, const msg::SupportPlan& plan,
                           std::uint32_t flight_lost) {
  set_time(msg_.header.stamp, o.stamp);
  msg_.uav_id = o.uav_id;
  msg_.flight = static_cast<std::uint8_t>(o.flight);
  msg_.flight_name = c_str(msg::to_string(o.flight));
  msg_.fault = static_cast<std::uint8_t>(o.fault);
  msg_.fault_text = c_str(msg::to_string(o.fault));
  msg_.plan_seq = plan.seq;
  msg_.plan_stops = static_cast<std::uint32_t>(plan.stops.count);
  msg_.total_lateness_s = plan.total_lateness_s;
  msg_.flight_lost = flight_lost;
}

PathMessage::PathMessage(std::size_t capacity) : poses_(capacity) {
  set_name(frame_, kMapFrame);
  msg_.header.frame_id = c_str(frame_);
  for (auto& p : poses_)
    p.header.frame_id = c_str(frame_);
  msg_.poses._buffer = poses_.data();
  msg_.poses._maximum = static_cast<std::uint32_t>(poses_.size());
}

void PathMessage::clear(TimePoint stamp) {
  set_time(msg_.header.stamp, stamp);
  msg_.poses._length = 0;
}

bool PathMessage::push(double x, double y, double z, double yaw_rad) {
  if (msg_.poses._length == poses_.size()) return false;
  geometry_msgs_msg_dds__PoseStamped_& p = poses_[msg_.poses._length++];
  p.header.stamp = msg_.header.stamp;
  set_pose(p.pose, x, y, z, yaw_rad);
  return true;
}

GridMessage::GridMessage(const GridGeometry2d& geometry)
    : geometry_(geometry), cells_(geometry.size(), kUnknown) {
  set_name(frame_, kMapFrame);
  msg_.header.frame_id = c_str(frame_);
  msg_.info.resolution = static_cast<float>(geometry.resolution());
  msg_.info.width = static_cast<std::uint32_t>(geometry.cells_x());
  msg_.info.height = static_cast<std::uint32_t>(geometry.cells_y());
  set_pose(msg_.info.origin, geometry.origin_x(), geometry.origin_y(), 0.0, 0.0);
  msg_.data._buffer = cells_.data();
  msg_.data._length = msg_.data._maximum = static_cast<std::uint32_t>(cells_.size());
}

void GridMessage::set_origin(const Vec2& origin) {
  geometry_ = GridGeometry2d(origin.x(), origin.y(), geometry_.resolution(), geometry_.cells_x(),
                             geometry_.cells_y());
  set_pose(msg_.info.origin, origin.x(), origin.y(), 0.0, 0.0);
}

void GridMessage::stamp_all(TimePoint stamp) {
  set_time(msg_.header.stamp, stamp);
  msg_.info.map_load_time = msg_.header.stamp;
}

MarkerArrayMessage::MarkerArrayMessage(std::size_t markers, std::size_t points)
    : markers_(markers), names_(markers), texts_(markers), points_(points) {
  set_name(frame_, kMapFrame);
  msg_.markers._buffer = markers_.data();
  msg_.markers._maximum = static_cast<std::uint32_t>(markers_.size());
}

void MarkerArrayMessage::clear(TimePoint stamp) {
  stamp_ = stamp;
  msg_.markers._length = 0;
  used_points_ = 0;
}

bool MarkerArrayMessage::delete_all() {
  const double at[4] = {0, 0, 0, 0}, scale[3] = {1, 1, 1};
  visualization_msgs_msg_dds__Marker_* m = add("", 0, 0, {0, 0, 0, 0}, at, scale);
  if (m != nullptr) m->action = 3;  // DELETEALL
  return m != nullptr;
}

visualization_msgs_msg_dds__Marker_* MarkerArrayMessage::add(std::string_view ns, std::int32_t id,
                                                             std::int32_t type, Rgba color,
                                                             const double (&at)[4],
                                                             const double (&scale)[3]) {
  const std::size_t i = msg_.markers._length;
  if (i == markers_.size()) return nullptr;
  visualization_msgs_msg_dds__Marker_& m = markers_[i];
  blank(m);
  set_header(m.header, frame_, stamp_);
  set_name(names_[i], ns);
  m.ns = c_str(names_[i]);
  m.id = id;
  m.type = type;
  m.action = 0;
  set_pose(m.pose, at[0], at[1], at[2], at[3]);
  m.scale = {scale[0], scale[1], scale[2]};
  m.color = {color.r, color.g, color.b, color.a};
  m.points._buffer = points_.data() + used_points_;
  ++msg_.markers._length;
  return &m;
}

bool MarkerArrayMessage::add_point(double x, double y, double z) {
  if (msg_.markers._length == 0 || used_points_ == points_.size()) return false;
  visualization_msgs_msg_dds__Marker_& m = markers_[msg_.markers._length - 1];
  points_[used_points_++] = {x, y, z};
  m.points._length = m.points._maximum = m.points._length + 1;
  return true;
}

void MarkerArrayMessage::set_text(std::string_view text) {
  if (msg_.markers._length == 0) return;
  const std::size_t i = msg_.markers._length - 1;
  set_name(texts_[i], text);
  markers_[i].text = c_str(texts_[i]);
}

void MarkerArrayMessage::add_ellipses(std::string_view ns, std::span<const Ellipse> ellipses,
                                      double z, Rgba color) {
  std::int32_t id = 0;
  for (const Ellipse& e : ellipses) {
    const Ellipse::Axes a = e.axes();
    const double at[4] = {e.center.x(), e.center.y(), z, a.angle_rad};
    const double scale[3] = {2.0 * a.a_m, 2.0 * a.b_m, 0.02};
    if (add(ns, id++, kCylinder, color, at, scale) == nullptr) return;
  }
}

TfMessage::TfMessage(std::size_t capacity) : children_(capacity), transforms_(capacity) {
  set_name(frame_, kMapFrame);
  msg_.transforms._buffer = transforms_.data();
  msg_.transforms._maximum = static_cast<std::uint32_t>(transforms_.size());
}

void TfMessage::clear() {
  msg_.transforms._length = 0;
}

bool TfMessage::add(TimePoint stamp, std::string_view child_frame, double x, double y, double z,
                    const double (&q_wxyz)[4]) {
  const std::size_t i = msg_.transforms._length;
  if (i == transforms_.size()) return false;
  geometry_msgs_msg_dds__TransformStamped_& t = transforms_[i];
  set_header(t.header, frame_, stamp);
  set_name(children_[i], child_frame);
  t.child_frame_id = c_str(children_[i]);
  t.transform.translation = {x, y, z};
  t.transform.rotation = {q_wxyz[1], q_wxyz[2], q_wxyz[3], q_wxyz[0]};
  ++msg_.transforms._length;
  return true;
}

std::int8_t occupancy_value(CellState s) {
  switch (s) {
    case CellState::kFree:
      return GridMessage::kFree;
    case CellState::kOccupied:
      return GridMessage::kOccupied;
    case CellState::kUnknown:
      break;
  }
  return GridMessage::kUnknown;
}

void set_prediction(MarkerArrayMessage& out, TimePoint stamp, std::span<const Ellipse> ellipses,
                    const Vec2* collision_point) {
  out.clear(stamp);
  (void)out.delete_all();
  out.add_ellipses("ellipses", ellipses, 0.01, {0.2F, 0.5F, 1.0F, 0.3F});
  if (collision_point != nullptr) {
    const double at[4] = {collision_point->x(), collision_point->y(), 0.2, 0.0};
    const double scale[3] = {0.3, 0.3, 0.3};
    (void)out.add("collision_point", 0, MarkerArrayMessage::kSphere, {1.0F, 0.1F, 0.1F, 0.9F}, at,
                  scale);
  }
}

void set_support_plan(const msg::SupportPlan& plan, PathMessage& path,
                      MarkerArrayMessage& markers) {
  path.clear(plan.stamp);
  markers.clear(plan.stamp);
  (void)markers.delete_all();
  std::int32_t id = 0;
  for (std::size_t k = 0; k < plan.stops.count; ++k) {
    const msg::SupportStop& st = plan.stops.items[k];
    (void)path.push(st.point_m[0], st.point_m[1], st.point_m[2], 0.0);
    const double at[4] = {st.point_m[0], st.point_m[1], st.point_m[2], 0.0};
    const double ball[3] = {0.4, 0.4, 0.4}, text[3] = {0.0, 0.0, 0.4};
    (void)markers.add("stops", id, MarkerArrayMessage::kSphere, {1.0F, 0.6F, 0.0F, 0.8F}, at, ball);
    (void)markers.add("labels", id++, MarkerArrayMessage::kText, {1, 1, 1, 1}, at, text);
    char label[48];
    std::snprintf(label, sizeof label, "%zu: ugv%u eta %.1f s by %.1f s", k + 1,
                  static_cast<unsigned>(st.ugv_id), st.eta_s, st.deadline_s);
    markers.set_text(label);
  }
}

}  // namespace colag::hal::ros2
