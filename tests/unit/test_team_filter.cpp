// UGV bodies in the world and the UAV's team filter (issue 19.4): the simulated sensors see the
// UGVs; the UAV keeps the live ones out of its map and maps the others like any obstacle.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <vector>

#include "colag/common/map_store.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "colag/uav/mapper.hpp"
#include "colag/uav/team_filter.hpp"

using namespace colag;
using namespace colag::sim;
using namespace colag::uav;
using namespace std::chrono_literals;

namespace {

// An empty world, the UAV 2 m up at the origin, UGVs where the test puts them.
struct Field {
  Field() {
    sim = std::make_unique<SimWorld>(SimWorldConfig{}, BoxWorld{}, clock);
    sim->add_uav(Vec3(0, 0, 2));
  }
  // Steps until the UAV's LiDAR has a scan; returns it and where the LiDAR was.
  hal::LidarScanView scan(Pose3& sensor) {
    hal::LidarScanView s;
    for (int i = 0; i < 20; ++i) {
      clock.advance(20ms);
      sim->step(clock.now(), 0.02);
      if (sim->uav_lidar().poll(s)) break;
    }
    sensor = sim->uav().state().pose;
    return s;
  }
  hal::scripted::ManualClock clock;
  std::unique_ptr<SimWorld> sim;
};

// Returns of the scan (world frame) within `radius` of `where` and between the two heights.
int returns_near(const hal::LidarScanView& scan, const Pose3& sensor, const Vec2& where,
                 double radius, double z0, double z1) {
  int n = 0;
  for (const hal::LidarPoint& p : scan.points) {
    const Vec3 w = sensor.q * Vec3(p.x_m, p.y_m, p.z_m) + sensor.p;
    n += (w.head<2>() - where).norm() <= radius && w.z() >= z0 && w.z() <= z1 ? 1 : 0;
  }
  return n;
}

// Occupied voxels above the ground layer around a UGV's body at `where`.
int occupied_around(const Mapper& map, const Vec2& where) {
  int n = 0;
  for (double z = 0.15; z < 0.45; z += 0.1) {
    for (double y = -0.35; y < 0.4; y += 0.1) {
      for (double x = -0.35; x < 0.4; x += 0.1)
        n += map.state(Vec3(where.x() + x, where.y() + y, z)) == VoxelState::kOccupied ? 1 : 0;
    }
  }
  return n;
}

hal::LidarPoint at(const Vec3& world, const Vec3& sensor) {
  const Vec3 d = world - sensor;
  return {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())};
}

}  // namespace

TEST(SimWorld, UgvBodiesAreSeenByTheLidarAndBlockTheCamerasView) {
  Field f;
  f.sim->add_ugv({Vec2(5.0, 0.0), 0.0});
  f.sim->add_ugv({Vec2(5.0, 3.0), 0.0});
  Pose3 sensor;
  const hal::LidarScanView s = f.scan(sensor);
  // Both bodies return the beams that reach them, up to their top (0.3 m), inside their disc.
  EXPECT_GT(returns_near(s, sensor, Vec2(5.0, 0.0), 0.26, 0.05, 0.31), 5);
  EXPECT_GT(returns_near(s, sensor, Vec2(5.0, 3.0), 0.26, 0.05, 0.31), 5);
  EXPECT_EQ(returns_near(s, sensor, Vec2(5.0, 0.0), 0.6, 0.32, 5.0), 0);  // nothing above it
  // A body in between blocks the view, except of its own tag.
  EXPECT_FALSE(f.sim->line_of_sight(Vec3(0, 0, 0.2), Vec3(9, 0, 0.2)));
  EXPECT_TRUE(f.sim->line_of_sight(Vec3(0, 0, 0.2), Vec3(5, 0, 0.2), 0));
  EXPECT_TRUE(f.sim->line_of_sight(Vec3(0, 0, 0.2), Vec3(9, 1.5, 0.2)));
}

TEST(SimWorld, TheBodiesMoveWithTheUgvs) {
  Field f;
  const int u = f.sim->add_ugv({Vec2(5.0, 0.0), 0.0});
  hal::can::CanDrive drive(f.sim->ugv_can(u), {}, {});
  for (int i = 0; i < 250; ++i) {  // 5 s at 0.5 m/s along +x
    f.clock.advance(20ms);
    (void)drive.command({f.clock.now(), 0.5, 0.0});
    f.sim->step(f.clock.now(), 0.02);
  }
  const Vec2 now = f.sim->ugv(u).pose().p;
  ASSERT_GT(now.x(), 6.5);
  Pose3 sensor;
  const hal::LidarScanView s = f.scan(sensor);
  EXPECT_GT(returns_near(s, sensor, now, 0.26, 0.05, 0.31), 5);
  EXPECT_EQ(returns_near(s, sensor, Vec2(5.0, 0.0), 0.26, 0.05, 0.31), 0);  // gone from the start
}

TEST(TeamFilter, DropsALocatedUgvsBodyKeepsTheGroundAndEverythingElse) {
  const Vec3 sensor_p(0, 0, 2);
  const Pose3 sensor{sensor_p, Quat::Identity()};
  const std::vector<hal::LidarPoint> points = {
      at({5.0, 0.0, 0.3}, sensor_p),   // its top
      at({5.2, 0.1, 0.15}, sensor_p),  // its side
      at({5.3, 0.0, 0.02}, sensor_p),  // the ground beside it
      at({5.0, 0.0, 1.0}, sensor_p),   // something hanging over it
      at({7.0, 0.0, 0.3}, sensor_p),   // an obstacle 2 m away
  };
  hal::LidarScanView scan;
  scan.points = points;
  const auto map_owner = std::make_unique<Mapper>();  // too big for the stack
  Mapper& map = *map_owner;
  TeamFilter filter;

  filter.begin();
  ASSERT_TRUE(filter.add(0, Vec2(5.0, 0.0), 0.05, 0ms, 0.0, 0.0));
  hal::LidarScanView out = filter.apply(scan, sensor, map);
  EXPECT_EQ(out.points.size(), 3u);
  EXPECT_EQ(filter.counters().dropped, 2u);

  // Too uncertain where it is: not located, nothing dropped (it is mapped, like any obstacle).
  filter.begin();
  EXPECT_FALSE(filter.add(0, Vec2(5.0, 0.0), 0.8, 0ms, 0.0, 0.0));
  EXPECT_EQ(filter.apply(scan, sensor, map).points.size(), points.size());
  // Nor from a status too old, nor from garbage.
  filter.begin();
  EXPECT_FALSE(filter.add(0, Vec2(5.0, 0.0), 0.05, 2s, 0.0, 0.0));
  EXPECT_FALSE(filter.add(1, Vec2(std::nan(""), 0.0), 0.05, 0ms, 0.0, 0.0));
  EXPECT_FALSE(filter.add(limits::kMaxUgvs, Vec2(5.0, 0.0), 0.05, 0ms, 0.0, 0.0));
  EXPECT_EQ(filter.apply(scan, sensor, map).points.size(), points.size());
}

// A moving UGV is where its reported speed takes it since the status (plus the link's latency):
// its front is dropped, and nothing behind the body.
TEST(TeamFilter, AMovingUgvIsDroppedAlongItsWayNotBehindIt) {
  const Vec3 sensor_p(0, 0, 2);
  const Pose3 sensor{sensor_p, Quat::Identity()};
  const std::vector<hal::LidarPoint> ahead = {at({5.6, 0.0, 0.3}, sensor_p)};
  hal::LidarScanView scan;
  scan.points = ahead;
  const auto map_owner = std::make_unique<Mapper>();  // too big for the stack
  Mapper& map = *map_owner;
  TeamFilter filter;
  filter.begin();
  (void)filter.add(0, Vec2(5.0, 0.0), 0.05, 300ms, 0.0, 0.5);  // heading +x at 0.5 m/s
  EXPECT_EQ(filter.apply(scan, sensor, map).points.size(), 0u);
  filter.begin();
  (void)filter.add(0, Vec2(5.0, 0.0), 0.05, 300ms, M_PI, 0.5);  // heading -x: 0.6 m behind it
  EXPECT_EQ(filter.apply(scan, sensor, map).points.size(), 1u);
}

// Mapped while nobody knew where it was (before its estimator had a fix), a UGV stands in its own
// map as an obstacle; once located, that is forgotten, and stays so while it is located.
TEST(TeamFilter, ForgetsTheBodyMappedBeforeTheUgvWasLocated) {
  Field f;
  const Vec2 where(5.0, 0.0);
  f.sim->add_ugv({where, 0.0});
  const auto map_owner = std::make_unique<Mapper>();  // too big for the stack
  Mapper& map = *map_owner;
  TeamFilter filter;
  const auto body_occupied = [&] { return occupied_around(map, where); };
  Pose3 sensor;
  hal::LidarScanView s = f.scan(sensor);
  filter.begin();  // nobody located
  map.insert_scan(sensor, filter.apply(s, sensor, map));
  ASSERT_GT(body_occupied(), 0);  // a silent UGV is an obstacle in the map

  for (int k = 0; k < 5; ++k) {
    s = f.scan(sensor);
    filter.begin();
    ASSERT_TRUE(filter.add(0, where, 0.1, 50ms, 0.0, 0.0));
    map.insert_scan(sensor, filter.apply(s, sensor, map));
    EXPECT_EQ(body_occupied(), 0) << "scan " << k;
  }
  EXPECT_EQ(filter.counters().located, 1u);
  EXPECT_GT(filter.counters().forgotten, 0u);
  EXPECT_GT(filter.counters().dropped, 0u);
  // The ground around it is still mapped.
  EXPECT_NE(map.state(Vec3(where.x() - 1.0, where.y(), 0.05)), VoxelState::kUnknown);
}

// Located first 0.85 m from where it stands (an outlying first relative pose), its body is mapped
// beside the dropped disc; once its estimate is sure enough that hits mapped within
// body_radius - u of it can only be its body, that body is forgotten.
TEST(TeamFilter, ForgetsItsBodyAgainWhenAStandingUgvsPositionIsCorrected) {
  Field f;
  const Vec2 where(5.0, 0.0), first_fix(5.8, 0.3);
  f.sim->add_ugv({where, 0.0});
  const auto map_owner = std::make_unique<Mapper>();
  Mapper& map = *map_owner;
  TeamFilter filter;
  const auto body_occupied = [&] { return occupied_around(map, where); };
  Pose3 sensor;
  for (int k = 0; k < 5; ++k) {
    const hal::LidarScanView s = f.scan(sensor);
    filter.begin();
    ASSERT_TRUE(filter.add(0, first_fix, 0.42, 50ms, 0.0, 0.0));
    map.insert_scan(sensor, filter.apply(s, sensor, map));
  }
  ASSERT_GT(body_occupied(), 0);  // the part of its body outside the dropped disc
  const std::uint64_t located = filter.counters().located;
  // Nothing is forgotten while the estimate is too uncertain to tell its body from beside it.
  for (const Vec2& p : {Vec2(5.7, 0.3), Vec2(5.1, 0.1)}) {
    const hal::LidarScanView s = f.scan(sensor);
    filter.begin();
    ASSERT_TRUE(filter.add(0, p, 0.3, 50ms, 0.0, 0.0));
    map.insert_scan(sensor, filter.apply(s, sensor, map));
  }
  EXPECT_EQ(filter.counters().located, located);
  for (int k = 0; k < 5; ++k) {
    const hal::LidarScanView s = f.scan(sensor);
    filter.begin();
    ASSERT_TRUE(filter.add(0, where, 0.03, 50ms, 0.0, 0.0));
    map.insert_scan(sensor, filter.apply(s, sensor, map));
  }
  EXPECT_EQ(filter.counters().located, located + 1);
  EXPECT_EQ(filter.counters().own_body, 1u);
  EXPECT_EQ(body_occupied(), 0);
}

// Forgetting a body forgets what was hit there, not the air around it that rays crossed.
TEST(Mapper, ForgetsWhatWasHitKeepsWhatWasSeenFree) {
  Field f;
  const Vec2 where(5.0, 0.0);
  f.sim->add_ugv({where, 0.0});
  const auto map_owner = std::make_unique<Mapper>();  // too big for the stack
  Mapper& map = *map_owner;
  Pose3 sensor;
  const hal::LidarScanView s = f.scan(sensor);
  map.insert_scan(sensor, s);
  const Vec3 body(where.x() - 0.15, where.y(), 0.25);  // its near face, seen from the UAV
  const Vec3 air(where.x() - 0.45, where.y(), 0.5);    // crossed by rays passing over it
  ASSERT_EQ(map.state(body), VoxelState::kOccupied);
  ASSERT_EQ(map.state(air), VoxelState::kFree);
  EXPECT_GT(map.forget(where, 0.6, 0.1, 0.6), 0u);
  EXPECT_EQ(map.state(body), VoxelState::kUnknown);
  EXPECT_EQ(map.state(air), VoxelState::kFree);
}

// The UAV cannot see the ground under a robot; the robot standing there is proof that nothing
// else is: the unknown cells its footprint covers are free in its own map, nothing else changes.
TEST(MapStore, TheGroundUnderTheRobotIsFreeInItsOwnMap) {
  const auto store = std::make_unique<MapStore>();  // all unknown (too big for the stack)
  const Vec2 me(1.0, 1.0);
  const auto covered = [&](int x, int y) {
    const Vec2 c = store->geometry().center_of({x, y});
    const Vec2 nearest = ((c - me).cwiseAbs() - Vec2::Constant(0.05)).cwiseMax(0.0);
    return nearest.norm() <= 0.25;
  };
  const int freed = store->free_under(me, 0.25);
  EXPECT_GE(freed, 16);  // at least the 4 x 4 cells inside a 0.5 m disc
  int free = 0;
  const CellIndex c = store->geometry().cell_of(me);
  for (int y = c.y - 6; y <= c.y + 6; ++y) {
    for (int x = c.x - 6; x <= c.x + 6; ++x) {
      EXPECT_EQ(store->state({x, y}), covered(x, y) ? CellState::kFree : CellState::kUnknown);
      free += store->state({x, y}) == CellState::kFree ? 1 : 0;
    }
  }
  EXPECT_EQ(free, freed);
  EXPECT_EQ(store->free_under(me, 0.25), 0);  // already free
  EXPECT_EQ(store->free_under(Vec2(std::nan(""), 0.0), 0.25), 0);
}
