// The rooms generator: walls with doorways, furniture clear of them, every room reachable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <deque>
#include <vector>

#include "colag/sim/world/room_world.hpp"

using namespace colag;
using namespace colag::sim;

namespace {

// How many cells of a 0.1 m grid over the arena (and 2 m around it) a robot of `radius` can
// stand on, and how many of those it reaches from `from` (4-connected).
struct Reach {
  std::size_t free = 0, reached = 0;
};
Reach flood(const BoxWorld& w, double radius, Vec2 from) {
  const double lo = w.min_x_m - 2.0, res = 0.1;
  const int n = static_cast<int>(std::lround((w.max_x_m - w.min_x_m + 4.0) / res));
  const auto centre = [&](int i) { return lo + (i + 0.5) * res; };
  std::vector<char> open(static_cast<std::size_t>(n) * n), seen(open.size());
  Reach r;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const bool ok = w.clearance(Vec2(centre(x), centre(y))) >= radius;
      open[static_cast<std::size_t>(y) * n + x] = ok ? 1 : 0;
      r.free += ok ? 1 : 0;
    }
  }
  std::deque<std::pair<int, int>> todo;
  const int fx = static_cast<int>((from.x() - lo) / res),
            fy = static_cast<int>((from.y() - lo) / res);
  todo.emplace_back(fx, fy);
  seen[static_cast<std::size_t>(fy) * n + fx] = 1;
  while (!todo.empty()) {
    const auto [x, y] = todo.front();
    todo.pop_front();
    ++r.reached;
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= n || ny >= n) continue;
      const std::size_t k = static_cast<std::size_t>(ny) * n + nx;
      if (open[k] == 0 || seen[k] != 0) continue;
      seen[k] = 1;
      todo.emplace_back(nx, ny);
    }
  }
  return r;
}

}  // namespace

TEST(RoomWorld, WallsWithOneDoorwayEachFurnitureClearOfThemEveryPlaceReachable) {
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    RoomGenConfig c;
    c.seed = seed;
    c.rooms_x = 4;
    c.rooms_y = 3;
    const auto w = generate_room_world(c);
    ASSERT_TRUE(w.is_ok()) << w.status().message();
    // Interior walls: (4-1) x 3 + (3-1) x 4 = 17 segments, each two pieces around its doorway.
    std::size_t walls = 0, furniture = 0;
    for (const Box& b : w.value().boxes) {
      const bool wall = b.half_size.minCoeff() == c.wall_thickness_m / 2;
      walls += wall ? 1 : 0;
      furniture += wall ? 0 : 1;
      EXPECT_LE(std::abs(b.center.x()) + b.half_size.x(), c.arena_half.x() + 1e-9);
      EXPECT_LE(std::abs(b.center.y()) + b.half_size.y(), c.arena_half.y() + 1e-9);
    }
    EXPECT_EQ(walls, 2u * 17u) << "seed " << seed;
    EXPECT_EQ(furniture, c.furniture);
    // A UGV with its planner's margin (0.25 m body + 0.4 m) gets everywhere there is room for
    // it, from outside the building: no room, doorway or corner is closed off.
    const Reach r = flood(w.value(), 0.65, Vec2(0.0, 15.0));
    EXPECT_EQ(r.reached, r.free) << "seed " << seed;
    EXPECT_GT(r.free, 60000u);
  }
  // Without doorways (narrower than the robot) the rooms are closed: the flood sees it.
  RoomGenConfig closed;
  closed.door_m = 1.2;
  const Reach r = flood(generate_room_world(closed).value(), 0.65, Vec2(0.0, 15.0));
  EXPECT_LT(r.reached, r.free);
}

TEST(RoomWorld, SameSeedSameBuildingAndBadSizesAreRefused) {
  RoomGenConfig c;
  c.seed = 9;
  const auto a = generate_room_world(c), b = generate_room_world(c);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  ASSERT_EQ(a.value().boxes.size(), b.value().boxes.size());
  for (std::size_t i = 0; i < a.value().boxes.size(); ++i)
    EXPECT_EQ(a.value().boxes[i].center, b.value().boxes[i].center);
  c.rooms_x = 0;
  EXPECT_EQ(generate_room_world(c).status().code(), Errc::kInvalidArgument);
  c.rooms_x = 20;  // 1.35 m rooms: no room for a 1.6 m doorway
  EXPECT_EQ(generate_room_world(c).status().code(), Errc::kInvalidArgument);
  c.rooms_x = 2;
  c.furniture = 500;
  EXPECT_EQ(generate_room_world(c).status().code(), Errc::kCapacityExceeded);
}
