#pragma once
// The altitude from which a down-looking camera sees the widest disc of tags. A cone of
// half-angle a reaches a tag h below it out to h tan(a), and the detector out to its range R:
// the disc is widest where the two meet, h = R cos(a) above the tags (75 deg and 5 m: 1.29 m,
// a disc of 4.8 m radius instead of 2.6 m from 0.7 m). A camera that sees in every direction (the
// paper's) sees most from as low as it may fly.
#include <algorithm>
#include <cmath>

namespace colag::uav {

struct CameraView {
  double range_m = 0.0;  // 0: not known, the altitude is left as configured
  double half_angle_deg = 180.0;
  double tag_height_m = 0.3;
};

// Between `lowest` (what the flight layer and the LiDAR were set up for) and `highest`.
inline double camera_altitude(const CameraView& v, double lowest, double highest) {
  if (!(v.range_m > 0.0) || v.half_angle_deg >= 90.0) return lowest;
  const double best = v.tag_height_m + v.range_m * std::cos(v.half_angle_deg * M_PI / 180.0);
  return std::clamp(best, lowest, std::max(lowest, highest));
}

}  // namespace colag::uav
