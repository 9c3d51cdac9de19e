#pragma once
// atan2 for loops over every LiDAR return, where glibc's (exact to the last bit, with the cost of
// that) took a tenth of a mission's time: a polynomial for atan on [0, 1] (Abramowitz & Stegun
// 4.4.49, |error| <= 2e-8 rad) and the octant's symmetries. Used where the angle is only binned
// (a LiDAR column is 5e-3 rad wide): not a replacement for std::atan2 in estimation.
#include <cmath>

namespace colag {

inline double fast_atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  if (!(hi > 0.0)) return std::atan2(y, x);  // the origin (signed zeros), or NaN
  if (std::isinf(hi)) return std::atan2(y, x);
  const double a = lo / hi, s = a * a;
  double r = 0.0028662257;
  r = r * s - 0.0161657367;
  r = r * s + 0.0429096138;
  r = r * s - 0.0752896400;
  r = r * s + 0.1065626393;
  r = r * s - 0.1420889944;
  r = r * s + 0.1999355085;
  r = r * s - 0.3333314528;
  r = a + a * s * r;
  if (ay > ax) r = M_PI_2 - r;
  if (x < 0.0) r = M_PI - r;
  return y < 0.0 ? -r : r;
}

}  // namespace colag
