#pragma once
// The board programs' configuration (ugv_fw / uav_fw --config robot.yaml), read with yaml-cpp
// at start-up. Every key is optional and defaults to the documented value (config/*.example.yaml
// lists them all); a present key with a wrong type or an out-of-range value is an error that
// names the key ("can.interface: expected a string"), and so is an unknown key (a typo must not
// silently fall back to a default on a robot).
#include <string>

#include "colag/platform/dds_security_config.hpp"
#include "colag/platform/realtime_executor.hpp"

namespace colag::board {

struct CommonBoardConfig {
  std::uint32_t dds_domain = 0;
  std::string dds_partition;
  platform::DdsSecurityConfig dds_security;  // dds.security: all six files, or none (off)
  platform::RealtimeOptions realtime{.fifo_priority = 50, .lock_memory = true};
};

}  // namespace colag::board
