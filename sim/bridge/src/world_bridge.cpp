#include "colag/sim/bridge/world_bridge.hpp"

#include <algorithm>
#include <cmath>

#include "colag/hal/dds/take_one.hpp"
#include "sim.h"

namespace colag::sim {

namespace {
std::int16_t mm(float v) {
  return static_cast<std::int16_t>(std::clamp(std::lround(v * 1000.0F), -32767L, 32767L));
}
}  // namespace

WorldBridge::WorldBridge(hal::sim::SimLink& link, SimWorld& world, bool with_uav,
                         bool uav_camera_only)
    : link_(link), world_(world), with_uav_(with_uav), uav_camera_only_(uav_camera_only) {
  xyz_mm_.reserve(std::size_t{3} * 2 * limits::kMaxLidarPoints);
}

void WorldBridge::step() {
  // Robots' commands -> their simulated motor controllers.
  while (hal::dds::take_one<colag_sim_CanFrame>(
      link_.reader(hal::sim::SimTopic::kCanFromRobot), [&](const auto& f) {
        if (f.robot_id >= world_.ugv_count()) {
          ++counters_.frames_for_unknown_robots;
          return;
        }
        hal::CanFrame frame;
        frame.id = f.can_id;
        frame.extended = f.extended;
        frame.dlc = f.dlc;
        std::copy_n(f.data, 8, frame.data);
        (void)world_.ugv_can(f.robot_id).send(frame, TimePoint::max());
        ++counters_.frames_from_robots;
      })) {
  }
  // Motor controllers' frames -> the robots.
  for (int i = 0; i < world_.ugv_count(); ++i) {
    hal::CanFrame frame;
    while (world_.ugv_can(i).receive(frame)) {
      colag_sim_CanFrame f{};
      f.robot_id = static_cast<std::uint16_t>(i);
      f.stamp_ns = to_nanoseconds(frame.stamp);
      f.can_id = frame.id;
      f.extended = frame.extended;
      f.dlc = frame.dlc;
      std::copy_n(frame.data, 8, f.data);
      if (dds_write(link_.writer(hal::sim::SimTopic::kCanToRobot), &f) >= 0)
        ++counters_.frames_to_robots;
    }
  }
  if (!with_uav_) return;
  if (!uav_camera_only_) fly_uav();

  // The camera's newest frame.
  hal::RelativePoseDetection dets[limits::kMaxRpeDetectionsPerFrame];
  const std::size_t n = world_.uav_camera().poll(dets);
  if (n > 0) {
    colag_sim_RpeDetection out[limits::kMaxRpeDetectionsPerFrame];
    colag_sim_RpeFrame frame{};
    frame.stamp_ns = to_nanoseconds(dets[0].stamp);
    for (std::size_t i = 0; i < n; ++i) {
      out[i] = {};
      out[i].ugv_id = dets[i].ugv_id;
      for (int k = 0; k < 3; ++k)
        out[i].position_m[k] = dets[i].ugv_in_uav.p[k];
      out[i].orientation_wxyz[0] = dets[i].ugv_in_uav.q.w();
      out[i].orientation_wxyz[1] = dets[i].ugv_in_uav.q.x();
      out[i].orientation_wxyz[2] = dets[i].ugv_in_uav.q.y();
      out[i].orientation_wxyz[3] = dets[i].ugv_in_uav.q.z();
      for (int k = 0; k < 16; ++k)
        out[i].covariance[k] = dets[i].covariance(k / 4, k % 4);
    }
    frame.detections._buffer = out;
    frame.detections._length = static_cast<std::uint32_t>(n);
    frame.detections._maximum = frame.detections._length;
    frame.detections._release = false;
    if (dds_write(link_.writer(hal::sim::SimTopic::kRpe), &frame) >= 0) ++counters_.rpe_frames;
  }
}

// The simulated flight controller, odometry and LiDAR (robot.hal sim).
void WorldBridge::fly_uav() {
  // Setpoints -> the UAV body.
  while (hal::dds::take_one<colag_sim_FlightSetpoint>(
      link_.reader(hal::sim::SimTopic::kSetpoint), [&](const auto& s) {
        hal::FlightSetpoint sp;
        sp.stamp = time_at_nanoseconds(s.stamp_ns);
        sp.position_m = Vec3(s.position_m[0], s.position_m[1], s.position_m[2]);
        sp.velocity_mps = Vec3(s.velocity_mps[0], s.velocity_mps[1], s.velocity_mps[2]);
        sp.acceleration_mps2 =
            Vec3(s.acceleration_mps2[0], s.acceleration_mps2[1], s.acceleration_mps2[2]);
        sp.yaw_rad = s.yaw_rad;
        (void)world_.uav().send_setpoint(sp);
        ++counters_.setpoints;
      })) {
  }
  // The UAV's state.
  hal::UavState st;
  while (world_.uav().poll(st)) {
    colag_sim_UavState s{};
    s.stamp_ns = to_nanoseconds(st.stamp);
    for (int k = 0; k < 3; ++k) {
      s.position_m[k] = st.pose.p[k];
      s.velocity_mps[k] = st.velocity_mps[k];
    }
    s.orientation_wxyz[0] = st.pose.q.w();
    s.orientation_wxyz[1] = st.pose.q.x();
    s.orientation_wxyz[2] = st.pose.q.y();
    s.orientation_wxyz[3] = st.pose.q.z();
    s.yaw_rate_radps = st.yaw_rate_radps;
    (void)dds_write(link_.writer(hal::sim::SimTopic::kUavState), &s);
  }
  // A LiDAR scan: returns, then misses, in millimetres.
  hal::LidarScanView scan;
  if (world_.uav_lidar().poll(scan)) {
    xyz_mm_.clear();
    for (const auto* part : {&scan.points, &scan.misses}) {
      for (const hal::LidarPoint& p : *part) {
        xyz_mm_.push_back(mm(p.x_m));
        xyz_mm_.push_back(mm(p.y_m));
        xyz_mm_.push_back(mm(p.z_m));
      }
    }
    colag_sim_LidarScan s{};
    s.stamp_ns = to_nanoseconds(scan.stamp);
    s.max_range_m = scan.max_range_m;
    s.return_count = static_cast<std::uint32_t>(scan.points.size());
    s.xyz_mm._buffer = xyz_mm_.data();
    s.xyz_mm._length = static_cast<std::uint32_t>(xyz_mm_.size());
    s.xyz_mm._maximum = s.xyz_mm._length;
    s.xyz_mm._release = false;
    if (dds_write(link_.writer(hal::sim::SimTopic::kLidar), &s) >= 0) {
      ++counters_.scans;
      counters_.scan_bytes += 2 * xyz_mm_.size();
    }
  }
}

}  // namespace colag::sim
