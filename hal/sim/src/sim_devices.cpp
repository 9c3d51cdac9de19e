#include "colag/hal/sim/sim_devices.hpp"

#include <algorithm>
#include <cmath>

#include "colag/hal/dds/take_one.hpp"
#include "sim.h"

namespace colag::hal::sim {
using dds::take_one;

Status SimCanBus::send(const hal::CanFrame& frame, TimePoint) {
  if (!hal::is_valid(frame)) {
    ++stats_.tx_failures;
    return {Errc::kInvalidArgument, "invalid CAN frame"};
  }
  colag_sim_CanFrame f{};
  f.robot_id = robot_;
  f.stamp_ns = to_nanoseconds(frame.stamp);
  f.can_id = frame.id;
  f.extended = frame.extended;
  f.dlc = frame.dlc;
  std::copy_n(frame.data, 8, f.data);
  if (dds_write(link_.writer(SimTopic::kCanFromRobot), &f) < 0) {
    ++stats_.tx_failures;
    return {Errc::kUnavailable, "sim CAN: write failed"};
  }
  ++stats_.tx_frames;
  return Status::ok();
}

bool SimCanBus::receive(hal::CanFrame& out) {
  bool got = false;
  while (!got &&
         take_one<colag_sim_CanFrame>(link_.reader(SimTopic::kCanToRobot), [&](const auto& f) {
           out = {};
           out.stamp = time_at_nanoseconds(
               f.stamp_ns);  // the world's time stamp, as on a hardware-stamped bus
           out.id = f.can_id;
           out.extended = f.extended;
           out.dlc = f.dlc;
           std::copy_n(f.data, 8, out.data);
           got = hal::is_valid(out);
           if (!got) ++stats_.error_frames;
         })) {
  }
  if (got) ++stats_.rx_frames;
  return got;
}

SimUavDevices::SimUavDevices(SimLink& link) : link_(link) {
  points_.reserve(limits::kMaxLidarPoints);
  misses_.reserve(limits::kMaxLidarPoints);
}

Status SimUavDevices::send_setpoint(const hal::FlightSetpoint& sp) {
  colag_sim_FlightSetpoint s{};
  s.stamp_ns = to_nanoseconds(sp.stamp);
  for (int i = 0; i < 3; ++i) {
    s.position_m[i] = sp.position_m[i];
    s.velocity_mps[i] = sp.velocity_mps[i];
    s.acceleration_mps2[i] = sp.acceleration_mps2[i];
  }
  s.yaw_rad = sp.yaw_rad;
  if (dds_write(link_.writer(SimTopic::kSetpoint), &s) < 0)
    return {Errc::kUnavailable, "sim flight controller: write failed"};
  return Status::ok();
}

bool SimUavDevices::poll(hal::UavState& out) {
  // The newest state: drain the queue.
  bool got = false;
  while (take_one<colag_sim_UavState>(link_.reader(SimTopic::kUavState), [&](const auto& s) {
    out.stamp = time_at_nanoseconds(s.stamp_ns);
    out.pose.p = Vec3(s.position_m[0], s.position_m[1], s.position_m[2]);
    out.pose.q = Quat(s.orientation_wxyz[0], s.orientation_wxyz[1], s.orientation_wxyz[2],
                      s.orientation_wxyz[3]);
    out.velocity_mps = Vec3(s.velocity_mps[0], s.velocity_mps[1], s.velocity_mps[2]);
    out.yaw_rate_radps = s.yaw_rate_radps;
    got = true;
  })) {
  }
  return got;
}

bool SimUavDevices::poll(hal::LidarScanView& out) {
  bool got = false;
  while (take_one<colag_sim_LidarScan>(link_.reader(SimTopic::kLidar), [&](const auto& scan) {
    const std::uint32_t values = scan.xyz_mm._length;
    if (values % 3 != 0 || scan.return_count > values / 3 ||
        values / 3 - scan.return_count > limits::kMaxLidarPoints ||
        scan.return_count > limits::kMaxLidarPoints || !std::isfinite(scan.max_range_m)) {
      ++malformed_;
      return;
    }
    points_.clear();
    misses_.clear();
    const std::int16_t* v = scan.xyz_mm._buffer;
    for (std::uint32_t i = 0; i < values / 3; ++i) {
      const std::size_t k = std::size_t{3} * i;
      const hal::LidarPoint p{v[k] * 1e-3F, v[k + 1] * 1e-3F, v[k + 2] * 1e-3F};
      (i < scan.return_count ? points_ : misses_).push_back(p);  // within the reserved capacity
    }
    out = {time_at_nanoseconds(scan.stamp_ns), scan.max_range_m, points_, misses_};
    got = true;
  })) {
  }
  return got;
}

std::size_t SimUavDevices::poll(std::span<hal::RelativePoseDetection> out) {
  std::size_t n = 0;
  bool got = false;
  while (take_one<colag_sim_RpeFrame>(link_.reader(SimTopic::kRpe), [&](const auto& frame) {
    n = 0;
    got = true;
    for (std::uint32_t i = 0; i < frame.detections._length && n < out.size(); ++i) {
      const colag_sim_RpeDetection& d = frame.detections._buffer[i];
      hal::RelativePoseDetection& r = out[n++];
      r.stamp = time_at_nanoseconds(frame.stamp_ns);
      r.ugv_id = d.ugv_id;
      r.ugv_in_uav.p = Vec3(d.position_m[0], d.position_m[1], d.position_m[2]);
      r.ugv_in_uav.q = Quat(d.orientation_wxyz[0], d.orientation_wxyz[1], d.orientation_wxyz[2],
                            d.orientation_wxyz[3]);
      for (int k = 0; k < 16; ++k)
        r.covariance(k / 4, k % 4) = d.covariance[k];
    }
  })) {
  }
  return got ? n : 0;
}

}  // namespace colag::hal::sim
