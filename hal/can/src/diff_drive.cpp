#include "colag/hal/can/diff_drive.hpp"

#include <algorithm>
#include <cmath>

namespace colag::hal::can {

WheelPair wheel_speeds(const DriveCommand& cmd, const WheelGeometry& geometry) {
  WheelPair w{cmd.v_mps - 0.5 * geometry.track_width_m * cmd.omega_radps,
              cmd.v_mps + 0.5 * geometry.track_width_m * cmd.omega_radps};
  const double peak = std::max(std::abs(w.left), std::abs(w.right));
  if (peak > geometry.max_wheel_speed_mps) {
    w.left *= geometry.max_wheel_speed_mps / peak;
    w.right *= geometry.max_wheel_speed_mps / peak;
  }
  return w;
}

bool twist_from_travel(const WheelPair& travel_m, double dt, const WheelGeometry& geometry,
                       WheelOdometrySample& out) {
  const double max_step = 3.0 * geometry.max_wheel_speed_mps * dt;
  if (!(dt > 0.0) || !std::isfinite(travel_m.left) || !std::isfinite(travel_m.right) ||
      std::abs(travel_m.left) > max_step || std::abs(travel_m.right) > max_step)
    return false;
  out.v_mps = 0.5 * (travel_m.left + travel_m.right) / dt;
  out.omega_radps = (travel_m.right - travel_m.left) / geometry.track_width_m / dt;
  return true;
}

}  // namespace colag::hal::can
