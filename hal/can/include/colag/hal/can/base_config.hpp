#pragma once
// Which CAN protocol the UGV's base speaks, and each protocol's settings (`can.protocol` in
// ugv_fw's configuration; the simulated world's and HIL's emulators take the same struct).
#include <cstdint>
#include <string_view>

#include "colag/hal/can/agilex_base.hpp"
#include "colag/hal/can/odrive_base.hpp"
#include "colag/hal/can/wheel_protocol.hpp"

namespace colag::hal::can {

enum class BaseProtocol : std::uint8_t {
  kColag,     // the project's own wheel protocol (hal/can/README.md)
  kOdrive,    // two ODrive axes, CAN Simple
  kAgilexV2,  // an AgileX base, protocol V2
};

inline const char* to_string(BaseProtocol p) {
  switch (p) {
    case BaseProtocol::kColag:
      return "colag";
    case BaseProtocol::kOdrive:
      return "odrive";
    case BaseProtocol::kAgilexV2:
      return "agilex_v2";
  }
  return "unknown";
}
inline bool parse_base_protocol(std::string_view text, BaseProtocol& out) {
  for (const BaseProtocol p :
       {BaseProtocol::kColag, BaseProtocol::kOdrive, BaseProtocol::kAgilexV2})
    if (text == to_string(p)) {
      out = p;
      return true;
    }
  return false;
}
inline constexpr const char* kBaseProtocolNames = "colag, odrive, agilex_v2";

struct BaseConfig {
  BaseProtocol protocol = BaseProtocol::kColag;
  WheelProtocolConfig colag;
  OdriveConfig odrive;
  AgilexConfig agilex;
};

}  // namespace colag::hal::can
