#pragma once
// The altitude from which a down-looking camera sees the widest disc of tags. A cone of
// half-angle a reaches a tag h below it out to h tan(a), and the detector out to its range R:
// the disc is widest where the two meet, h = R cos(a) above the tags (75 deg and 5 m: 1.29 m,
// a disc of 4.8 m radius instead of 2.6 m from 0.7 m). A camera that sees in every direction (the
// paper's) sees most from as low as it may fly. How high it may fly is the LiDAR's to say: the
// steeper its lowest beam, the smaller the blind disc it leaves under the UAV.
#include <algorithm>
#include <cmath>
#include <limits>

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

// How far from the point under it a camera `altitude_m` up sees a tag: where the tag leaves its
// cone or its detector's range. Infinite where the camera is not described or the tag is not
// below it.
inline double camera_reach(const CameraView& v, double altitude_m) {
  const double above_tag = altitude_m - v.tag_height_m;
  if (!(v.range_m > 0.0) || !(above_tag > 0.0)) return std::numeric_limits<double>::infinity();
  double reach = std::sqrt(std::max(0.0, v.range_m * v.range_m - above_tag * above_tag));
  if (v.half_angle_deg < 90.0)
    reach = std::min(reach, above_tag * std::tan(v.half_angle_deg * M_PI / 180.0));
  return reach;
}

// The blind disc a LiDAR whose lowest beam points `lowest_elevation_deg` (negative: down) leaves
// on the ground band from `band_low_m` up, flying at `altitude_m`: (h - band_low) / tan(-lowest).
// 0 looking straight down; NaN where it cannot look down, flies below the band or is not
// described (NaN).
inline double lidar_blind_radius(double lowest_elevation_deg, double altitude_m,
                                 double band_low_m) {
  const double down = -lowest_elevation_deg * M_PI / 180.0;
  const double height = altitude_m - band_low_m;
  if (!(down > 0.0) || !(height > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return down >= M_PI / 2.0 ? 0.0 : height / std::tan(down);
}

// The highest a LiDAR whose lowest beam points `lowest_elevation_deg` (negative: down; see
// blind_cone_elevation_deg) may fly and still map the ground band from `band_low_m` up out to
// `blind_radius_m` around the point under it (lidar_blind_radius() solved for the altitude). A
// LiDAR that cannot
// look down, or one not described (NaN), gives nothing above `lowest`; one looking straight
// down is limited by `highest` alone.
inline double lidar_altitude_limit(double lowest_elevation_deg, double band_low_m,
                                   double blind_radius_m, double lowest, double highest) {
  const double down = -lowest_elevation_deg * M_PI / 180.0;
  if (!(down > 0.0) || !(blind_radius_m > 0.0) || !std::isfinite(band_low_m)) return lowest;
  if (down >= M_PI / 2.0) return std::max(lowest, highest);
  return std::clamp(band_low_m + blind_radius_m * std::tan(down), lowest,
                    std::max(lowest, highest));
}

}  // namespace colag::uav
