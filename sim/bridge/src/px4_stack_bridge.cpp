#include "colag/sim/bridge/px4_stack_bridge.hpp"

#include <cstring>

#include "colag/common/frames.hpp"
#include "colag/common/limits.hpp"
#include "colag/hal/dds/take_one.hpp"
#include "colag/hal/ros2/ros2_names.hpp"
#include "px4_msgs.h"
#include "px4_msgs_v1_15.h"
#include "ros2_msgs.h"

namespace colag::sim {

namespace {

using hal::dds::take_one;
using hal::px4::Px4Release;
using hal::px4::Px4Topic;

// livox_ros_driver2's PointCloud2 (xfer_format 0): x y z intensity (float32), tag line (uint8),
// timestamp (float64), packed: 26 bytes a point.
constexpr std::uint32_t kLivoxPointStep = 26;

builtin_interfaces_msg_dds__Time_ ros_time(TimePoint t) {
  const std::int64_t ns = to_nanoseconds(t);
  return {static_cast<std::int32_t>(ns / 1'000'000'000),
          static_cast<std::uint32_t>(ns % 1'000'000'000)};
}

std::uint64_t px4_us(TimePoint t) {
  return static_cast<std::uint64_t>(std::max<std::int64_t>(0, to_nanoseconds(t) / 1000));
}

}  // namespace

bool Px4StackBridge::init(const Px4StackConfig& config, std::string& error) {
  config_ = config;
  vehicle_ = std::make_unique<Px4Vehicle>(config.vehicle, world_.uav());
  cloud_.resize(limits::kMaxLidarPoints * kLivoxPointStep);
  if (!dds_.init(config.dds_domain)) {
    error = "PX4 stack: " + dds_.last_error();
    return false;
  }
  const Px4Release r = config.release;
  const std::string& ns = config.ns;
  using hal::px4::px4_dds_topic;
  offboard_in_ = dds_.reader(px4_dds_topic(r, Px4Topic::kOffboardControlMode, ns),
                             px4_msgs_msg_dds__OffboardControlMode__desc, 8);
  setpoint_in_ = dds_.reader(px4_dds_topic(r, Px4Topic::kTrajectorySetpoint, ns),
                             px4_msgs_msg_dds__TrajectorySetpoint__desc, 8);
  command_in_ = dds_.reader(px4_dds_topic(r, Px4Topic::kVehicleCommand, ns),
                            px4_msgs_msg_dds__VehicleCommand__desc, 8);
  status_out_ = dds_.writer(px4_dds_topic(r, Px4Topic::kVehicleStatus, ns),
                            r == Px4Release::kV115 ? px4_msgs_v1_15_msg_dds__VehicleStatus__desc
                                                   : px4_msgs_msg_dds__VehicleStatus__desc,
                            "px4_msgs::msg::dds_::VehicleStatus_");
  ack_out_ = dds_.writer(px4_dds_topic(r, Px4Topic::kVehicleCommandAck, ns),
                         px4_msgs_msg_dds__VehicleCommandAck__desc);
  odometry_out_ = dds_.writer(px4_dds_topic(r, Px4Topic::kVehicleOdometry, ns),
                              px4_msgs_msg_dds__VehicleOdometry__desc);
  lio_out_ = dds_.writer(hal::ros2::ros2_dds_topic(config.odometry_topic),
                         nav_msgs_msg_dds__Odometry__desc);
  cloud_out_ = dds_.writer(hal::ros2::ros2_dds_topic(config.lidar_topic),
                           sensor_msgs_msg_dds__PointCloud2__desc);
  if (!offboard_in_ || !setpoint_in_ || !command_in_ || !status_out_ || !ack_out_ ||
      !odometry_out_ || !lio_out_ || !cloud_out_) {
    error = "PX4 stack: " + dds_.last_error();
    return false;
  }
  return true;
}

void Px4StackBridge::fail_safe() {
  vehicle_->fail_safe(position_);
}

void Px4StackBridge::pilot_takes_over() {
  vehicle_->pilot_takes_over(position_);
}

void Px4StackBridge::step(TimePoint now) {
  // What the firmware sends PX4 (a silent agent drops it: nothing reaches PX4 either).
  while (take_one<px4_msgs_msg_dds__OffboardControlMode_>(offboard_in_, [&](const auto& m) {
    if (silent_ || !m.position) return;  // only position control is played
    vehicle_->on_heartbeat(now);
    ++counters_.heartbeats;
  })) {
  }
  while (take_one<px4_msgs_msg_dds__TrajectorySetpoint_>(setpoint_in_, [&](const auto& m) {
    if (silent_) return;
    hal::FlightSetpoint sp;
    sp.stamp = now;
    sp.position_m = frames::ned_to_enu(Vec3(m.position[0], m.position[1], m.position[2]));
    sp.velocity_mps = frames::ned_to_enu(Vec3(m.velocity[0], m.velocity[1], m.velocity[2]));
    const Vec3 a(m.acceleration[0], m.acceleration[1], m.acceleration[2]);
    sp.acceleration_mps2 = all_finite(a) ? frames::ned_to_enu(a) : Vec3::Zero();
    sp.yaw_rad = frames::ned_yaw_to_enu(m.yaw);
    if (!all_finite(sp.position_m) || !all_finite(sp.velocity_mps)) return;
    vehicle_->on_setpoint(now, sp);
    ++counters_.setpoints;
  })) {
  }
  while (take_one<px4_msgs_msg_dds__VehicleCommand_>(command_in_, [&](const auto& m) {
    if (silent_) return;
    ++counters_.commands;
    px4_msgs_msg_dds__VehicleCommandAck_ ack{};
    ack.timestamp = px4_us(now);
    ack.command = m.command;
    ack.result = vehicle_->on_command(now, m.command, m.param1, m.param2);
    ack.target_system = m.source_system;
    ack.target_component = m.source_component;
    (void)dds_write(ack_out_, &ack);
  })) {
  }

  // The odometry the world gives it (and FAST-LIO): PX4 flies on it.
  hal::UavState st;
  while (world_.uav().poll(st)) {
    position_ = st.pose.p;
    publish_lio(st);  // FAST-LIO is its own process: PX4's silence does not stop it
    if (silent_) continue;
    ++counters_.odometry;
    px4_msgs_msg_dds__VehicleOdometry_ o{};
    o.timestamp = px4_us(now);
    o.timestamp_sample = px4_us(st.stamp);
    o.pose_frame = 1;
    const Vec3 p = frames::enu_to_ned(st.pose.p);
    const Quat q = frames::enu_flu_to_ned_frd(st.pose.q);
    const Vec3 v = frames::enu_to_ned(st.velocity_mps);
    for (int i = 0; i < 3; ++i) {
      o.position[i] = static_cast<float>(p[i]);
      o.velocity[i] = static_cast<float>(v[i]);
    }
    o.q[0] = static_cast<float>(q.w());
    o.q[1] = static_cast<float>(q.x());
    o.q[2] = static_cast<float>(q.y());
    o.q[3] = static_cast<float>(q.z());
    o.velocity_frame = 1;
    o.angular_velocity[2] = static_cast<float>(-st.yaw_rate_radps);  // FRD z is down
    (void)dds_write(odometry_out_, &o);
  }
  vehicle_->step(now, position_);

  // The Livox driver's cloud: returns only, in the sensor frame.
  hal::LidarScanView scan;
  if (world_.uav_lidar().poll(scan)) {  // the Livox driver: not PX4's
    const std::size_t n = std::min(scan.points.size(), limits::kMaxLidarPoints);
    for (std::size_t i = 0; i < n; ++i) {
      std::uint8_t* p = cloud_.data() + i * kLivoxPointStep;
      const float xyzi[4] = {scan.points[i].x_m, scan.points[i].y_m, scan.points[i].z_m, 100.0F};
      std::memcpy(p, xyzi, sizeof xyzi);
      p[16] = 0;                                 // tag
      p[17] = static_cast<std::uint8_t>(i % 4);  // line
      const double t = to_seconds(scan.stamp.time_since_epoch());
      std::memcpy(p + 18, &t, sizeof t);
    }
    char names[7][10] = {"x", "y", "z", "intensity", "tag", "line", "timestamp"};
    sensor_msgs_msg_dds__PointField_ fields[7] = {
        {names[0], 0, 7, 1},  {names[1], 4, 7, 1},  {names[2], 8, 7, 1}, {names[3], 12, 7, 1},
        {names[4], 16, 2, 1}, {names[5], 17, 2, 1}, {names[6], 18, 8, 1}};
    sensor_msgs_msg_dds__PointCloud2_ c{};
    c.header.stamp = ros_time(scan.stamp);
    c.header.frame_id = const_cast<char*>("livox_frame");
    c.height = 1;
    c.width = static_cast<std::uint32_t>(n);
    c.fields._buffer = fields;
    c.fields._length = c.fields._maximum = 7;
    c.fields._release = false;
    c.is_bigendian = false;
    c.point_step = kLivoxPointStep;
    c.row_step = static_cast<std::uint32_t>(n) * kLivoxPointStep;
    c.data._buffer = cloud_.data();
    c.data._length = c.data._maximum = c.row_step;
    c.data._release = false;
    c.is_dense = true;
    if (dds_write(cloud_out_, &c) >= 0) ++counters_.clouds;
  }
  publish_status(now);
}

void Px4StackBridge::publish_lio(const hal::UavState& st) {
  nav_msgs_msg_dds__Odometry_ lio{};
  lio.header.stamp = ros_time(st.stamp);
  lio.header.frame_id = const_cast<char*>("camera_init");
  lio.child_frame_id = const_cast<char*>("body");
  lio.pose.pose.position = {st.pose.p.x(), st.pose.p.y(), st.pose.p.z()};
  lio.pose.pose.orientation = {st.pose.q.x(), st.pose.q.y(), st.pose.q.z(), st.pose.q.w()};
  (void)dds_write(lio_out_, &lio);  // FAST-LIO leaves the twist empty
}

void Px4StackBridge::publish_status(TimePoint now) {
  const Px4Vehicle& v = *vehicle_;
  const bool changed =
      v.nav_state() != last_nav_ || v.armed() != last_armed_ || v.failsafe() != last_failsafe_;
  if (silent_ || (!changed && !elapsed(now, last_status_, config_.status_period))) return;
  last_status_ = now;
  last_nav_ = v.nav_state();
  last_armed_ = v.armed();
  last_failsafe_ = v.failsafe();
  ++counters_.statuses;
  auto fill = [&](auto& s) {
    s.timestamp = px4_us(now);
    s.arming_state = v.armed() ? 2 : 1;
    s.nav_state = v.nav_state();
    s.nav_state_user_intention = v.nav_state();
    s.failsafe = v.failsafe();
    s.vehicle_type = 1;  // rotary wing
    s.system_id = 1;
    s.component_id = 1;
    s.pre_flight_checks_pass = true;
  };
  if (config_.release == Px4Release::kV115) {
    px4_msgs_v1_15_msg_dds__VehicleStatus_ s{};
    fill(s);
    (void)dds_write(status_out_, &s);
  } else {
    px4_msgs_msg_dds__VehicleStatus_ s{};
    fill(s);
    (void)dds_write(status_out_, &s);
  }
}

}  // namespace colag::sim
