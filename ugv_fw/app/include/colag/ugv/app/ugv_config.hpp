#pragma once
// ugv_fw's configuration (see colag/board/config.hpp for the rules, config/ugv.example.yaml for
// keys).
#include <string>

#include "colag/board/config.hpp"
#include "colag/hal/can/base_config.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/ugv/ugv_nav_config.hpp"

namespace colag::ugv {

struct UgvBoardConfig {
  board::CommonBoardConfig common;
  UgvNavConfig nav;  // with the schedule table (rates: changes its periods)
  std::string can_interface = "can0";
  hal::can::BaseConfig base;  // can.protocol and its section
  hal::can::WheelGeometry wheels;
  // Its last pose, kept across a restart of the program (resume_state.hpp); empty: not kept.
  std::string state_file;
  double state_max_age_s = 300.0;
};

// False with `error` = "FILE: key.path: problem".
bool load_ugv_config(const std::string& path, UgvBoardConfig& out, std::string& error);
// The same for a document in memory (tests, fuzzing); `name` stands for the file in errors.
bool parse_ugv_config(const std::string& text, const std::string& name, UgvBoardConfig& out,
                      std::string& error);

}  // namespace colag::ugv
