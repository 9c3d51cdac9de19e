#pragma once
// Where the UAV circles a UGV that stopped against its own edge: a collision predicted at its
// first step (at the start, where no one has mapped the ground round it yet, or pressed against
// an obstacle). The usual support orbit (2 m round a point backed off behind the collision) keeps
// that ground inside the LiDAR's blind disc or behind the UGV's own body, and the UGV stood until
// its covariance had shrunk to a cell (~9 s at every start). Circling the UGV itself just outside
// the blind disc, every side of its body is seen unshadowed from that side, and the camera, which
// reaches further than the LiDAR's blind disc, keeps seeing its tag.
#include <algorithm>
#include <cmath>
#include <limits>

#include "colag/uav/camera_altitude.hpp"

namespace colag::uav {

// The radius of that circle: the blind disc of a LiDAR whose lowest beam points
// `lowest_elevation_deg` (negative: down), flying at `altitude_m`, on the ground band from
// `band_low_m` up, plus `beyond_blind_m`, and never less than `smallest_m`. NaN where no circle
// does both, and the usual orbit is better: the disc reaches beyond 0.3 m inside the camera's
// horizontal reach of a tag (`camera`; not described: no limit), or the LiDAR is not described
// (NaN), does not look down or flies below the band.
inline double edge_orbit_radius(double lowest_elevation_deg, double altitude_m, double band_low_m,
                                const CameraView& camera, double beyond_blind_m,
                                double smallest_m) {
  const double blind = lidar_blind_radius(lowest_elevation_deg, altitude_m, band_low_m);
  if (!std::isfinite(blind) || !std::isfinite(beyond_blind_m))
    return std::numeric_limits<double>::quiet_NaN();
  const double radius = std::max(smallest_m, blind + beyond_blind_m);
  return radius <= camera_reach(camera, altitude_m) - 0.3
             ? radius
             : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace colag::uav
