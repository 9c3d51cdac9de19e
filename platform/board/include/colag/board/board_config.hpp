#pragma once
// The board programs' configuration (ugv_fw / uav_fw --config robot.yaml), read with yaml-cpp
// at start-up. Every key is optional and defaults to the documented value (config/*.example.yaml
// lists them all); a present key with a wrong type or an out-of-range value is an error that
// names the key ("can.interface: expected a string"), and so is an unknown key (a typo must not
// silently fall back to a default on a robot).
#include <string>

#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/linux/camera_rpe.hpp"
#include "colag/platform/realtime_executor.hpp"
#include "colag/ugv/ugv_nav_config.hpp"

namespace colag::board {

struct CommonBoardConfig {
  std::uint32_t dds_domain = 0;
  std::string dds_partition;
  platform::RealtimeOptions realtime{.fifo_priority = 50, .lock_memory = true};
};

struct UgvBoardConfig {
  CommonBoardConfig common;
  ugv::UgvNavConfig nav;
  std::string can_interface = "can0";
  hal::can::WheelProtocolConfig protocol;
  hal::can::WheelGeometry wheels;
  Duration control_period = std::chrono::milliseconds(20);
  Duration planning_period = std::chrono::milliseconds(100);
};

struct UavBoardConfig {
  CommonBoardConfig common;
  RobotId id = 0;
  linux_hal::TagPoseConfig rpe;
  linux_hal::CameraSource camera;
  std::string calibration_file;  // OpenCV calibration YAML, required
};

// False with `error` = "FILE: key.path: problem".
bool load_ugv_config(const std::string& path, UgvBoardConfig& out, std::string& error);
bool load_uav_config(const std::string& path, UavBoardConfig& out, std::string& error);

}  // namespace colag::board
