#pragma once
// Differential-drive kinematics every wheel-level driver shares: a body twist to wheel speeds
// within the wheels' limit, and wheel travel to a body twist.
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/drive.hpp"
#include "colag/hal/wheel_odometry.hpp"

namespace colag::hal::can {

struct WheelPair {
  double left = 0.0;
  double right = 0.0;
};

// (v, omega) -> wheel speeds (m/s), scaled together so that neither exceeds the limit (the
// turn is kept, the speed gives way).
WheelPair wheel_speeds(const DriveCommand& cmd, const WheelGeometry& geometry);

// Wheel travel (m) over `dt` seconds -> a body twist; false (a fault) when a wheel moved faster
// than 3x its limit, or dt is not positive. The factor leaves room for stamp jitter.
bool twist_from_travel(const WheelPair& travel_m, double dt, const WheelGeometry& geometry,
                       WheelOdometrySample& out);

}  // namespace colag::hal::can
