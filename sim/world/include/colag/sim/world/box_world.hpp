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
  double height_m = 0.0;          // from the ground (z = 0)

  bool contains(const Vec3& p) const {
    return p.z() >= 0.0 && p.z() <= height_m && std::abs(p.x() - center.x()) <= half_size.x() &&
           std::abs(p.y() - center.y()) <= half_size.y();
  }
  // Distance from a ground point to the footprint (0 inside).
  double distance(const Vec2& p) const {
    const Vec2 d = ((p - center).cwiseAbs() - half_size).cwiseMax(0.0);
    return d.norm();
  }
};

struct BoxWorld {
  std::vector<Box> boxes;  // host-side: built once before a run
  double min_x_m = -13.5, max_x_m = 13.5, min_y_m = -13.5, max_y_m = 13.5;  // the arena

  // Distance from a ground point to the nearest box footprint (a large value if none).
  double clearance(const Vec2& p) const;
  bool occupied(const Vec3& p) const;
};

struct MapGenConfig {
  std::size_t boxes = 80;  // 40 = the paper's sparse map, 80 = dense
  double arena_half_m = 13.5;
  double min_center_distance_m = 1.5;
  double small_fraction = 0.56;  // share of 0.7 m boxes; the rest are 0.9 m
  double small_side_m = 0.7;
  double large_side_m = 0.9;
  double height_m = 0.6;
  std::uint64_t seed = 1;
};

// Rejection sampling with a bounded number of attempts; fails (kCapacityExceeded) when the
// arena cannot hold that many boxes at that spacing.
Result<BoxWorld> generate_box_world(const MapGenConfig& config);

}  // namespace colag::sim
