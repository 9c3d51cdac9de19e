#pragma once
#include "colag/common/geometry.hpp"
#include "colag/common/status.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/uav_odometry.hpp"

namespace colag::hal {

// A full-state setpoint for the UAV's flight controller (position loop runs there).
struct FlightSetpoint {
  TimePoint stamp;
  Vec3 position_m = Vec3::Zero();
  Vec3 velocity_mps = Vec3::Zero();
  Vec3 acceleration_mps2 = Vec3::Zero();
  double yaw_rad = 0.0;
};

// What the flight controller does for the mission, and why not when it does not.
struct FlightStatus {
  msg::UavFlight state = msg::UavFlight::kInControl;
  msg::FlightFault fault = msg::FlightFault::kNone;
};

class FlightController {
 public:
  virtual ~FlightController() = default;
  virtual Status send_setpoint(const FlightSetpoint& sp) = 0;
  // Called every control period, before send_setpoint: keeps the link to the flight controller
  // alive (heartbeats, mode and arming requests) and says whether it flies the mission. A
  // controller that needs no upkeep (the simulated one) is always in control.
  virtual FlightStatus update(TimePoint now) {
    (void)now;
    return {};
  }
  // The mission is over: land and disarm (update() goes on reporting kLanding).
  virtual void land(TimePoint now) { (void)now; }
};

}  // namespace colag::hal
