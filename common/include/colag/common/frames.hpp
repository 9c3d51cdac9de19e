#pragma once
// Every conversion between this project's frames and a flight stack's, in one place.
// This project (and ROS, REP-103/105): world ENU (x east, y north, z up), body FLU (x forward,
// y left, z up). PX4: world NED (x north, y east, z down), body FRD (x forward, y right, z down).
// Both pairs share their origin; each conversion is its own inverse. Drivers convert once, at
// the driver; nothing else in the firmware sees NED or FRD.
#include "colag/common/geometry.hpp"

namespace colag::frames {

// A world-frame point or vector, ENU <-> NED.
inline Vec3 enu_to_ned(const Vec3& v) {
  return {v.y(), v.x(), -v.z()};
}
inline Vec3 ned_to_enu(const Vec3& v) {
  return enu_to_ned(v);
}

// A body-frame vector, FLU <-> FRD.
inline Vec3 flu_to_frd(const Vec3& v) {
  return {v.x(), -v.y(), -v.z()};
}
inline Vec3 frd_to_flu(const Vec3& v) {
  return flu_to_frd(v);
}

namespace detail {
// NED <- ENU: half a turn about the (1, 1, 0) axis; FLU <- FRD: half a turn about x. Each is
// its own inverse.
inline Quat ned_from_enu() {
  return {0.0, M_SQRT1_2, M_SQRT1_2, 0.0};
}
inline Quat flu_from_frd() {
  return {0.0, 1.0, 0.0, 0.0};
}
}  // namespace detail

// An attitude (body -> world), FLU-in-ENU <-> FRD-in-NED.
inline Quat enu_flu_to_ned_frd(const Quat& q_enu_flu) {
  return (detail::ned_from_enu() * q_enu_flu * detail::flu_from_frd()).normalized();
}
inline Quat ned_frd_to_enu_flu(const Quat& q_ned_frd) {
  return (detail::ned_from_enu() * q_ned_frd * detail::flu_from_frd()).normalized();
}

// A heading: ENU yaw (from east, counter-clockwise) <-> NED yaw (from north, clockwise).
inline double enu_yaw_to_ned(double yaw_rad) {
  return wrap_angle(M_PI / 2.0 - yaw_rad);
}
inline double ned_yaw_to_enu(double yaw_rad) {
  return enu_yaw_to_ned(yaw_rad);
}

}  // namespace colag::frames
