#include "colag/sim/world/room_world.hpp"

#include <algorithm>

#include "colag/common/random.hpp"

namespace colag::sim {

namespace {

// A wall along one axis from `from` to `to` at `at` on the other axis, with a doorway of `door`
// starting at `gap` (along the wall): two boxes (either may be empty and is then left out).
void add_wall(BoxWorld& world, bool along_x, double at, double from, double to, double gap,
              const RoomGenConfig& c) {
  const double t = c.wall_thickness_m / 2;
  const auto piece = [&](double a, double b) {
    if (b - a < 1e-6) return;
    const double mid = (a + b) / 2, half = (b - a) / 2;
    Box box;
    box.center = along_x ? Vec2(mid, at) : Vec2(at, mid);
    box.half_size = along_x ? Vec2(half, t) : Vec2(t, half);
    box.height_m = c.wall_height_m;
    world.boxes.push_back(box);
  };
  piece(from, gap);
  piece(gap + c.door_m, to);
}

}  // namespace

Result<BoxWorld> generate_room_world(const RoomGenConfig& c) {
  if (c.rooms_x < 1 || c.rooms_y < 1 || c.rooms_x > 100 || c.rooms_y > 100)
    return Status{Errc::kInvalidArgument, "rooms: 1..100 along each axis"};
  const Vec2 half = c.arena_half;
  const double room_x = 2.0 * half.x() / c.rooms_x, room_y = 2.0 * half.y() / c.rooms_y;
  if (!(c.door_m > 0.0 && c.door_margin_m >= 0.0 && c.wall_thickness_m > 0.0) ||
      std::min(room_x, room_y) < c.door_m + 2 * c.door_margin_m + c.wall_thickness_m)
    return Status{Errc::kInvalidArgument, "rooms too small for their doorways"};
  BoxWorld world;
  world.min_x_m = -half.x();
  world.max_x_m = half.x();
  world.min_y_m = -half.y();
  world.max_y_m = half.y();
  Rng rng(c.seed);
  // Where a doorway starts along a wall segment [a, b], on the 0.1 m grid.
  const auto door_at = [&](double a, double b) {
    const double lo = a + c.door_margin_m + c.wall_thickness_m / 2;
    const double hi = b - c.door_margin_m - c.wall_thickness_m / 2 - c.door_m;
    const auto steps = static_cast<std::uint64_t>(std::max(0.0, (hi - lo) / 0.1)) + 1;
    return lo + 0.1 * static_cast<double>(rng.below(steps));
  };
  // Walls between columns of rooms (along y at x = const), one segment per room row, each with
  // its doorway; then those between rows of rooms.
  for (int i = 1; i < c.rooms_x; ++i) {
    const double x = -half.x() + i * room_x;
    for (int j = 0; j < c.rooms_y; ++j) {
      const double a = -half.y() + j * room_y, b = a + room_y;
      add_wall(world, false, x, a, b, door_at(a, b), c);
    }
  }
  for (int j = 1; j < c.rooms_y; ++j) {
    const double y = -half.y() + j * room_y;
    for (int i = 0; i < c.rooms_x; ++i) {
      const double a = -half.x() + i * room_x, b = a + room_x;
      add_wall(world, true, y, a, b, door_at(a, b), c);
    }
  }
  const std::size_t walls = world.boxes.size();
  MapGenConfig paper;  // furniture: the paper's box sizes
  const auto steps = [](double h) {
    return static_cast<std::uint64_t>(std::llround(2.0 * h / 0.1)) + 1;
  };
  for (std::size_t attempt = 0;
       attempt < 10000 * (c.furniture + 1) && world.boxes.size() < walls + c.furniture; ++attempt) {
    const double ky = static_cast<double>(rng.below(steps(half.y())));
    const double kx = static_cast<double>(rng.below(steps(half.x())));
    const double side =
        rng.uniform() < paper.small_fraction ? paper.small_side_m : paper.large_side_m;
    Box box;
    box.center = Vec2(-half.x() + 0.1 * kx, -half.y() + 0.1 * ky);
    box.half_size = Vec2::Constant(side / 2);
    box.height_m = paper.height_m;
    // Clear of every wall and other box by furniture_clear_m: footprint to footprint, measured
    // from the box's corners outwards (its centre's clearance less its half diagonal).
    if (((box.center.cwiseAbs().array() + side / 2) > half.array()).any()) continue;  // inside
    if (world.clearance(box.center) - side / std::sqrt(2.0) < c.furniture_clear_m) continue;
    world.boxes.push_back(box);
  }
  if (world.boxes.size() < walls + c.furniture)
    return Status{Errc::kCapacityExceeded, "rooms too small for that much furniture"};
  return world;
}

}  // namespace colag::sim
