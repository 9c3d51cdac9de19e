#include "colag/sim/world/box_world.hpp"

#include <cmath>
#include <limits>

#include "colag/common/random.hpp"

namespace colag::sim {

double BoxWorld::clearance(const Vec2& p, double low, double high) const {
  double best = std::numeric_limits<double>::max();
  for (const Box& b : boxes) {
    if (b.reaches(low, high)) best = std::min(best, b.distance(p));
  }
  return best;
}

bool BoxWorld::occupied(const Vec3& p) const {
  for (const Box& b : boxes) {
    if (b.contains(p)) return true;
  }
  return false;
}

Result<BoxWorld> generate_box_world(const MapGenConfig& config) {
  BoxWorld world;
  const Vec2 half = config.arena_half;
  world.min_x_m = -half.x();
  world.max_x_m = half.x();
  world.min_y_m = -half.y();
  world.max_y_m = half.y();
  Rng rng(config.seed);
  const auto steps = [](double h) {
    return static_cast<std::uint64_t>(std::llround(2.0 * h / 0.1)) + 1;
  };
  const std::size_t max_attempts = 10000 * (config.boxes + 1);
  for (std::size_t attempt = 0; attempt < max_attempts && world.boxes.size() < config.boxes;
       ++attempt) {
    // Centres on the 0.1 m grid, as in the paper's maps. Two statements: the order in which a
    // constructor's arguments are evaluated is unspecified (GCC drew y first on x86-64 and x
    // first on aarch64: the same seed gave another map on a board). y first, as the shipped maps.
    const double ky = static_cast<double>(rng.below(steps(half.y())));
    const double kx = static_cast<double>(rng.below(steps(half.x())));
    const Vec2 c(-half.x() + 0.1 * kx, -half.y() + 0.1 * ky);
    bool ok = true;
    for (const Box& b : world.boxes) {
      if ((b.center - c).norm() < config.min_center_distance_m) {
        ok = false;
        break;
      }
    }
    if (!ok) continue;
    if (config.pillars) {
      // A whole number of 0.1 m steps in [lo, hi].
      const auto draw = [&](double lo, double hi) {
        const auto k0 = static_cast<std::uint64_t>(std::llround(lo / 0.1));
        const auto k1 = static_cast<std::uint64_t>(std::llround(hi / 0.1));
        return 0.1 * static_cast<double>(k0 + rng.below(k1 - k0 + 1));
      };
      const double sx = draw(config.pillar_min_side_m, config.pillar_max_side_m);
      const double sy = draw(config.pillar_min_side_m, config.pillar_max_side_m);
      const double h = draw(config.pillar_min_height_m, config.pillar_max_height_m);
      world.boxes.push_back({c, Vec2(sx / 2, sy / 2), h});
      continue;
    }
    const double side =
        rng.uniform() < config.small_fraction ? config.small_side_m : config.large_side_m;
    world.boxes.push_back({c, Vec2::Constant(side / 2), config.height_m});
  }
  if (world.boxes.size() < config.boxes) {
    return Status{Errc::kCapacityExceeded, "arena too small for that many boxes at that spacing"};
  }
  return world;
}

}  // namespace colag::sim
