#pragma once
// The simulated world's obstacles: axis-aligned boxes standing on the ground, as in the paper's
// evaluation maps (0.7 x 0.7 m and 0.9 x 0.9 m footprints, 0.6 m tall, centres on a 0.1 m grid
// at least 1.5 m apart inside a 27 x 27 m arena). Host-side only (sim/).
#include <cstdint>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/common/status.hpp"

namespace colag::sim {

struct Box {
  Vec2 center = Vec2::Zero();
  Vec2 half_size = Vec2::Zero();  // half extents along x and y
  double height_m = 0.0;          // its top, from the ground (z = 0)
  double base_m = 0.0;            // its bottom: 0 standing on the ground, > 0 overhead

  bool contains(const Vec3& p) const {
    return p.z() >= base_m && p.z() <= height_m && std::abs(p.x() - center.x()) <= half_size.x() &&
           std::abs(p.y() - center.y()) <= half_size.y();
  }
  // Whether it reaches into the height band [low, high] (what a body in that band can hit).
  bool reaches(double low, double high) const { return base_m <= high && height_m >= low; }
  // Distance from a ground point to the footprint (0 inside).
  double distance(const Vec2& p) const {
    const Vec2 d = ((p - center).cwiseAbs() - half_size).cwiseMax(0.0);
    return d.norm();
  }
};

struct BoxWorld {
  std::vector<Box> boxes;  // host-side: built once before a run
  double min_x_m = -13.5, max_x_m = 13.5, min_y_m = -13.5, max_y_m = 13.5;  // the arena

  // Distance from a ground point to the nearest box footprint (a large value if none), of the
  // boxes reaching into the band [low, high] (every box by default).
  double clearance(const Vec2& p, double low = -1e9, double high = 1e9) const;
  bool occupied(const Vec3& p) const;
};

struct MapGenConfig {
  std::size_t boxes = 80;                  // 40 = the paper's sparse map, 80 = dense
  Vec2 arena_half = Vec2::Constant(13.5);  // the field: [-x, x] x [-y, y]
  double min_center_distance_m = 1.5;
  double small_fraction = 0.56;  // share of 0.7 m boxes; the rest are 0.9 m
  double small_side_m = 0.7;
  double large_side_m = 0.9;
  double height_m = 0.6;
  // Pillars instead of the paper's two boxes (when `pillars`): each side and the height drawn
  // uniformly on the 0.1 m grid from these ranges (taller and thinner than the paper's boxes).
  bool pillars = false;
  double pillar_min_side_m = 0.2, pillar_max_side_m = 0.5;
  double pillar_min_height_m = 0.6, pillar_max_height_m = 1.2;
  std::uint64_t seed = 1;
};

// Rejection sampling with a bounded number of attempts; fails (kCapacityExceeded) when the
// arena cannot hold that many boxes at that spacing.
Result<BoxWorld> generate_box_world(const MapGenConfig& config);

}  // namespace colag::sim
