#pragma once
// A point cloud (a PCD map: the paper's, ours, or a real site's) as the simulated world's boxes.
// 1. The ground is fitted, not assumed at z = 0: the most populated 1 cm height bin near the
//    bottom of the cloud, refined to the median of the points within 5 cm of it; its spread
//    (MAD) is the ground noise. Heights are then taken from the ground.
// 2. Points more than the noise floor (4 sigma, at least 3 cm) above it belong to obstacles,
//    binned into 0.1 m columns. A column matters to a UGV by its real vertical extent against
//    the UGV's body band [band_low_m, band_high_m] (the firmware's): topping out below the band
//    it is clutter a UGV drives over (dropped); reaching into the band it stands on the ground
//    up to its highest point; lying wholly above the band it is an overhead obstacle (a bridge
//    deck, a canopy) a UGV passes under, kept as a raised box for the sensors.
// 3. Neighbouring columns with the same extent merge into rectangles (a row's runs, then equal
//    runs of consecutive rows), sized by their points plus half a point spacing: the paper's
//    box maps come back box for box; a wall, an L or a ring keeps its shape.
#include <cstddef>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/sim/world/box_world.hpp"

namespace colag::sim {

struct CloudWorldConfig {
  double resolution_m = 0.1;
  double band_low_m = 0.1;   // lower obstacles: clutter a UGV drives over
  double band_high_m = 0.7;  // obstacles wholly higher: overhead, a UGV passes under
};

struct GroundFit {
  double z_m = 0.0;
  double sigma_m = 0.0;    // the ground points' spread (robust: 1.4826 MAD)
  std::size_t points = 0;  // within 5 cm of the ground
};
GroundFit fit_ground(const std::vector<Vec3>& points);

struct CloudWorldReport {
  GroundFit ground;
  std::size_t obstacle_columns = 0;  // 0.1 m columns that reach the band
  std::size_t clutter_columns = 0;   // columns topping out below it (dropped)
  std::size_t overhead_boxes = 0;    // boxes wholly above it
  Vec2 extent_m = Vec2::Zero();      // the cloud's size in x and y
};

BoxWorld box_world_from_points(const std::vector<Vec3>& points, const CloudWorldConfig& config = {},
                               CloudWorldReport* report = nullptr);

}  // namespace colag::sim
