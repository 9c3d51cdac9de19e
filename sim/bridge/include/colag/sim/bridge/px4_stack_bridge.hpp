#pragma once
// colag_world playing the UAV's flight stack over DDS, on the wire formats of the real thing:
// PX4 through its uXRCE-DDS agent (px4_msgs under ROS 2 names: offboard_control_mode,
// trajectory_setpoint, vehicle_command in; vehicle_status, vehicle_command_ack,
// vehicle_odometry out), FAST-LIO's nav_msgs/Odometry and the Livox driver's PointCloud2
// (xfer_format 0 layout). The firmware's PX4 and ROS 2 drivers fly the simulated UAV exactly as
// they would fly the aircraft. PX4's behaviour is Px4Vehicle's; the odometry and the clouds are
// the world's, with the world profile's imperfections.
#include <cstdint>
#include <string>
#include <vector>

#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/px4/px4_release.hpp"
#include "colag/sim/world/px4_vehicle.hpp"
#include "colag/sim/world/sim_world.hpp"

namespace colag::sim {

struct Px4StackConfig {
  std::uint32_t dds_domain = 0;
  hal::px4::Px4Release release = hal::px4::Px4Release::kV116;
  std::string ns;
  std::string odometry_topic = "/Odometry";  // FAST-LIO
  std::string lidar_topic = "/livox/lidar";  // livox_ros_driver2, xfer_format 0
  Px4VehicleConfig vehicle;
  Duration status_period = std::chrono::milliseconds(200);
};

struct Px4StackCounters {
  std::uint64_t heartbeats = 0;
  std::uint64_t setpoints = 0;
  std::uint64_t commands = 0;
  std::uint64_t statuses = 0;
  std::uint64_t odometry = 0;
  std::uint64_t clouds = 0;
};

class Px4StackBridge {
 public:
  explicit Px4StackBridge(SimWorld& world) : world_(world) {}
  bool init(const Px4StackConfig& config, std::string& error);
  // Every control period (~10-20 ms): PX4's inputs, its vehicle, then what it and the other
  // drivers publish.
  void step(TimePoint now);

  // Faults: PX4 (the agent, the link) falls silent (FAST-LIO and the Livox driver go on: other
  // processes); PX4 fails safe on its own; a pilot switches it to position mode.
  void set_silent(bool silent) { silent_ = silent; }
  void fail_safe();
  void pilot_takes_over();

  const Px4Vehicle& vehicle() const { return *vehicle_; }
  const Px4StackCounters& counters() const { return counters_; }

 private:
  void publish_status(TimePoint now);
  void publish_lio(const hal::UavState& st);

  SimWorld& world_;
  Px4StackConfig config_;
  hal::dds::DeviceParticipant dds_;
  dds_entity_t offboard_in_ = 0, setpoint_in_ = 0, command_in_ = 0;
  dds_entity_t status_out_ = 0, ack_out_ = 0, odometry_out_ = 0, lio_out_ = 0, cloud_out_ = 0;
  std::unique_ptr<Px4Vehicle> vehicle_;
  TimePoint last_status_ = kNever;
  std::uint8_t last_nav_ = 0;
  bool last_armed_ = false, last_failsafe_ = false;
  Vec3 position_ = Vec3::Zero();  // PX4's estimate: the odometry it is given
  bool silent_ = false;
  std::vector<std::uint8_t> cloud_;  // PointCloud2 data, sized once
  Px4StackCounters counters_;
};

}  // namespace colag::sim
