#pragma once
// The UAV board program's mission composition (its topology): the flight controller, odometry,
// LiDAR and camera the configuration names, the DDS transport, the UAV task, and the executor
// table built from the UAV's schedule table (UavSchedule). uav_fw's main runs it; tests build it
// the same way. Devices: robot.hal px4 (PX4 over its agent, LiDAR-inertial odometry and LiDAR
// from their ROS 2 drivers, the camera) or sim (colag_world over the sim link: SITL). It holds
// the mapper's grids (tens of MB): the program keeps it in static storage.
#include <optional>
#include <string>

#include "colag/hal/sim/sim_devices.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/realtime_executor.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/uav/app/uav_config.hpp"
#include "colag/uav/app/uav_ros2_bridge.hpp"
#include "colag/uav/uav_supervisor_task.hpp"

namespace colag::uav {

class UavBoard {
 public:
  // `time_scale` != 1 only with the simulated devices (SITL).
  UavBoard(const UavBoardConfig& config, double time_scale);
  UavBoard(const UavBoard&) = delete;
  UavBoard& operator=(const UavBoard&) = delete;

  // Opens the devices and DDS, builds the task and the table, calls every task's init. False
  // with `error` saying which device failed and why.
  bool start(std::string& error);
  // Runs until `end` or a stop request (stop_on_signals).
  void run(TimePoint end);
  // The mission is over: with PX4, land and wait until it has disarmed (false: it did not
  // within `limit`, or a pilot or a failsafe has the aircraft). Call after run().
  bool land(Duration limit);
  // The mission's counters, for the log at exit.
  void print_counters(const char* program) const;

  platform::RealtimeExecutor& executor() { return executor_; }
  const platform::Schedule& schedule() const { return executor_.schedule(); }

 private:
  UavBoardConfig config_;
  bool open_devices(std::string& error);

  platform::RealtimeExecutor executor_;
  std::optional<hal::sim::SimLink> sim_link_;
  std::optional<hal::sim::SimUavDevices> sim_devices_;
  std::optional<hal::px4::Px4FlightController> px4_;
  std::optional<hal::ros2::Ros2Odometry> ros2_odometry_;
  std::optional<hal::ros2::Ros2Lidar> ros2_lidar_;
  std::optional<linux_hal::CameraRpe> camera_rpe_;
  // The devices the task runs on (one of the above each).
  hal::FlightController* flight_ = nullptr;
  hal::OdometrySource* odometry_ = nullptr;
  hal::Lidar* lidar_ = nullptr;
  hal::RelativePoseSensor* camera_ = nullptr;
  platform::dds::DdsTransport dds_;
  platform::WorkerPool pool_{1};  // mapping may use a second core
  std::optional<platform::TransportPump> pump_;
  std::optional<UavSupervisorTask> task_;
  std::optional<UavRos2Bridge> ros2_;  // with `ros2.enabled`
};

}  // namespace colag::uav
