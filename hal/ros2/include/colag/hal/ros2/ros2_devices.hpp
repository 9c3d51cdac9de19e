#pragma once
// The UAV's LiDAR-inertial odometry and LiDAR from their ROS 2 drivers, read over DDS without a
// ROS installation: nav_msgs/Odometry (FAST-LIO's /Odometry) and sensor_msgs/PointCloud2
// (livox_ros_driver2 with xfer_format 0, or FAST-LIO's /cloud_registered_body).
//
// Stamps: a sample is stamped when it is taken, by the board's clock, less a configured
// latency: the publishers' header stamps are on another clock (ROS time, often the wall clock
// of another computer) and are not trusted for fusion.
#include <cstdint>
#include <string>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/hal/clock.hpp"
#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/hal/ros2/point_cloud.hpp"
#include "colag/hal/ros2/ros2_names.hpp"

namespace colag::hal::ros2 {

struct Ros2OdometryConfig {
  std::uint32_t dds_domain = 0;
  std::string topic = "/Odometry";
  // The odometry's world frame (FAST-LIO: camera_init, the IMU where it started) in the
  // mission's world, and the UAV body in the odometry's child frame (FAST-LIO: body, the IMU).
  Pose3 origin;
  Pose3 body_to_uav;
  Duration latency = std::chrono::milliseconds(20);
};

struct Ros2OdometryCounters {
  std::uint64_t received = 0;
  std::uint64_t rejected = 0;  // not finite, a zero quaternion
};

class Ros2Odometry final : public OdometrySource {
 public:
  explicit Ros2Odometry(const Clock& clock) : clock_(clock) {}
  bool init(const Ros2OdometryConfig& config, std::string& error);
  bool poll(UavState& out) override;
  const Ros2OdometryCounters& counters() const { return counters_; }

 private:
  const Clock& clock_;
  Ros2OdometryConfig config_;
  dds::DeviceParticipant dds_;
  dds_entity_t reader_ = 0;
  // FAST-LIO leaves the twist empty: the velocity is then the pose's rate of change.
  bool have_last_ = false;
  UavState last_;
  Vec3 velocity_ = Vec3::Zero();
  Ros2OdometryCounters counters_;
};

struct Ros2LidarConfig {
  std::uint32_t dds_domain = 0;
  std::string topic = "/livox/lidar";
  float min_range_m = 0.3F;                          // nearer returns are the aircraft itself
  float max_range_m = 8.0F;                          // the mapper's range
  Duration latency = std::chrono::milliseconds(50);  // a 10 Hz frame: half its sweep, plus the link
};

struct Ros2LidarCounters {
  std::uint64_t clouds = 0;
  std::uint64_t malformed = 0;  // refused by cloud_layout
  std::uint64_t points = 0;
  std::uint64_t kept = 0;
  std::uint64_t thinned = 0;
};

class Ros2Lidar final : public Lidar {
 public:
  explicit Ros2Lidar(const Clock& clock) : clock_(clock) {}
  bool init(const Ros2LidarConfig& config, std::string& error);
  // Returns only: the Mid-360's pattern is not repetitive, so no beam can be said to have missed.
  bool poll(LidarScanView& out) override;
  const Ros2LidarCounters& counters() const { return counters_; }
  // Why the last cloud was refused ("" if none was).
  const char* last_refusal() const { return refusal_; }

 private:
  const Clock& clock_;
  Ros2LidarConfig config_;
  dds::DeviceParticipant dds_;
  dds_entity_t reader_ = 0;
  std::vector<LidarPoint> points_;  // capacity kMaxLidarPoints, at init
  Ros2LidarCounters counters_;
  const char* refusal_ = "";
};

}  // namespace colag::hal::ros2
