#pragma once
// uav_fw's configuration (see colag/board/config.hpp for the rules, config/uav.example.yaml for
// keys).
#include <string>

#include "colag/board/config.hpp"
#include "colag/hal/linux/camera_rpe.hpp"
#include "colag/hal/px4/px4_flight_controller.hpp"
#include "colag/hal/ros2/ros2_devices.hpp"
#include "colag/uav/camera_altitude.hpp"
#include "colag/uav/no_return_beams.hpp"

namespace colag::uav {

struct UavBoardConfig {
  board::CommonBoardConfig common;
  RobotId id = 0;
  // robot.hal: "sim" (colag_world's devices over the sim link: SITL), "px4" (PX4 over its
  // uXRCE-DDS agent, LiDAR-inertial odometry and LiDAR from their ROS 2 drivers, the camera),
  // "board" (the camera alone: --camera-test).
  bool sim_hal = false;
  bool px4_hal = false;
  hal::px4::Px4DriverConfig px4;
  bool odometry_from_px4 = false;  // odometry.source: px4 (VehicleOdometry) or fast_lio
  hal::ros2::Ros2OdometryConfig odometry;
  hal::ros2::Ros2LidarConfig lidar;
  Pose3 lidar_mount;        // LiDAR frame -> UAV body (lidar.mount)
  bool sim_camera = false;  // camera.device: sim (colag_world's camera over the sim link)
  linux_hal::TagPoseConfig rpe;
  linux_hal::CameraSource camera;
  std::string calibration_file;  // OpenCV calibration YAML, required
  // What the supervisor is told of its sensors (see UavSupervisorConfig): the LiDAR's beam
  // pattern (its beams without a return are free space; its lowest beam bounds the altitude)
  // and the camera's view of the tags (where it flies to see most of them).
  LidarBeamPattern lidar_pattern;
  CameraView camera_view;
  // fleet: with other UAVs (see UavSupervisorConfig): how far apart they keep, when a silent
  // one is gone, and how long a silent one flies on before its own failsafe.
  double separation_m = 1.5;
  Duration peer_timeout = std::chrono::seconds(2);
  Duration peer_failsafe = std::chrono::seconds(1);
};

// False with `error` = "FILE: key.path: problem".
bool load_uav_config(const std::string& path, UavBoardConfig& out, std::string& error);
// The same for a document in memory (tests, fuzzing); `name` stands for the file in errors.
bool parse_uav_config(const std::string& text, const std::string& name, UavBoardConfig& out,
                      std::string& error);

}  // namespace colag::uav
