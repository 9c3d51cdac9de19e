#pragma once
#include "colag/common/geometry.hpp"
#include "colag/common/status.hpp"
#include "colag/common/time.hpp"

namespace colag::hal {

// A full-state setpoint for the UAV's flight controller (position loop runs there).
struct FlightSetpoint {
  TimePoint stamp;
  Vec3 position_m = Vec3::Zero();
  Vec3 velocity_mps = Vec3::Zero();
  Vec3 acceleration_mps2 = Vec3::Zero();
  double yaw_rad = 0.0;
};

class FlightController {
 public:
  virtual ~FlightController() = default;
  virtual Status send_setpoint(const FlightSetpoint& sp) = 0;
};

}  // namespace colag::hal
