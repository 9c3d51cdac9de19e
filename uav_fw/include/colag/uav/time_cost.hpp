#pragma once
// The UAV's travel-time model for scheduling (paper Eq. (8)-(11)). Between support points the
// UAV cruises: d / v_max. The first leg starts from the UAV's current velocity: along the line
// to the target it accelerates at a_max from v_tan (the component of its full velocity vector
// towards the target; the original code used only the x component) up to v_max, then cruises.
// With dis_a = (v_max^2 - v_tan^2) / (2 a_max):
//   dis_a >= d : t = (sqrt(v_tan^2 + 2 a_max d) - v_tan) / a_max   (never reaches v_max; the
//                paper's formula has dis_a under the root here, a typo fixed)
//   otherwise  : t = (v_max - v_tan) / a_max + (d - dis_a) / v_max
// v_tan < 0 (moving away) is covered by the same kinematics; v_tan is capped at v_max.
#include "colag/common/geometry.hpp"

namespace colag::uav {

struct FlightLimits {
  double v_max_mps = 3.0;
  double a_max_mps2 = 1.0;
};

double cruise_time_s(const Vec2& from, const Vec2& to, const FlightLimits& limits);
double first_leg_time_s(const Vec2& uav_position, const Vec2& uav_velocity, const Vec2& target,
                        const FlightLimits& limits);

}  // namespace colag::uav
