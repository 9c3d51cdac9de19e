// Returns-only LiDAR scans: the beams that saw nothing, inferred from the sensor's pattern.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "colag/common/random.hpp"
#include "colag/sim/world/lidar_simulator.hpp"
#include "colag/uav/mapper.hpp"
#include "colag/uav/no_return_beams.hpp"

using namespace colag;
using namespace colag::uav;

namespace {

LidarBeamPattern pattern_of(const sim::LidarPattern& p) {
  return {p.beams, p.lowest_elevation_deg, p.elevation_step_deg, p.columns};
}

sim::BoxWorld one_box_world() {
  sim::BoxWorld world;
  world.boxes.push_back({Vec2(3.0, 0.0), Vec2(0.45, 0.45), 0.6});
  world.boxes.push_back({Vec2(-2.0, 4.0), Vec2(1.0, 0.3), 1.8});
  return world;
}

}  // namespace

TEST(NoReturnBeams, InfersExactlyTheBeamsTheSensorHadNoReturnFor) {
  auto lidar = std::make_unique<sim::LidarSimulator>();
  const sim::BoxWorld world = one_box_world();
  const Pose3 sensor{Vec3(0.02, 0.03, 1.0), Quat::Identity()};
  std::span<const hal::LidarPoint> points, misses;
  lidar->scan(world, sensor, points, misses);
  ASSERT_GT(misses.size(), 1000u);
  NoReturnBeams inference(pattern_of(lidar->pattern()));
  const hal::LidarScanView out = inference.complete({TimePoint{}, 8.0F, points, {}}, sensor, 0.0);
  EXPECT_EQ(out.points.size(), points.size());
  // Nothing here is closer than the 1 m minimum, and the beams the ground-plane rule leaves out
  // are exactly those that reach the ground within range (returns, all of them).
  EXPECT_EQ(out.misses.size(), misses.size());
  EXPECT_EQ(inference.counters().returns_lost, 0u);
  EXPECT_EQ(inference.counters().returns_off_pattern, 0u);
  // Each inferred miss is one of the sensor's, to float precision.
  std::size_t matched = 0;
  for (std::size_t k = 0; k < misses.size(); k += 97) {
    const Vec3 m(misses[k].x_m, misses[k].y_m, misses[k].z_m);
    for (const hal::LidarPoint& q : out.misses) {
      if ((Vec3(q.x_m, q.y_m, q.z_m) - m).norm() < 1e-3) {
        ++matched;
        break;
      }
    }
  }
  EXPECT_EQ(matched, (misses.size() + 96) / 97);

  // Every tenth return lost: those of beams aimed at the ground within range are lost returns
  // (nothing inferred), the others (the box's, above the ground's horizon) inferred misses.
  std::vector<hal::LidarPoint> kept;
  std::size_t lost_low = 0, lost_high = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (k % 10 != 0) {
      kept.push_back(points[k]);
      continue;
    }
    const Vec3 d = Vec3(points[k].x_m, points[k].y_m, points[k].z_m).normalized();
    (sensor.p.z() + 8.0 * d.z() < 0.0 ? lost_low : lost_high) += 1;
  }
  ASSERT_GT(lost_low, 100u);
  ASSERT_GT(lost_high, 10u);
  NoReturnBeams lossy(pattern_of(lidar->pattern()));
  const hal::LidarScanView some = lossy.complete({TimePoint{}, 8.0F, kept, {}}, sensor, 0.0);
  EXPECT_EQ(some.misses.size(), misses.size() + lost_high);
  EXPECT_EQ(lossy.counters().returns_lost, lost_low);
}

TEST(NoReturnBeams, LeavesAScanWithMissesOrFromAnUnknownPatternAsItIs) {
  const hal::LidarPoint hit{2.0F, 0.0F, 0.0F}, miss{8.0F, 0.0F, 0.0F};
  const Pose3 high{Vec3(0.0, 0.0, 10.0), Quat::Identity()};  // no beam reaches the ground
  NoReturnBeams known(LidarBeamPattern{32, -25.2, 1.2, 1200});
  const hal::LidarScanView listed =
      known.complete({TimePoint{}, 8.0F, {&hit, 1}, {&miss, 1}}, high, 0.0);
  EXPECT_EQ(listed.misses.size(), 1u);
  NoReturnBeams unknown;  // no pattern: a non-repetitive scanner, or not configured
  EXPECT_FALSE(unknown.knows_pattern());
  EXPECT_TRUE(unknown.complete({TimePoint{}, 8.0F, {&hit, 1}, {}}, high, 0.0).misses.empty());
  NoReturnBeams too_big(LidarBeamPattern{1000, -25.2, 1.2, 1200});  // beyond the limits
  EXPECT_FALSE(too_big.knows_pattern());
  // A return between two beams' elevations is not one of this sensor's: counted, not binned.
  const hal::LidarPoint odd{2.0F, 0.0F, static_cast<float>(2.0 * std::tan(0.6 * M_PI / 180.0))};
  const hal::LidarScanView out = known.complete({TimePoint{}, 8.0F, {&odd, 1}, {}}, high, 0.0);
  EXPECT_EQ(out.misses.size(), 32u * 1200u);
  EXPECT_EQ(known.counters().returns_off_pattern, 1u);
}

// A returns-only driver losing 5 % of its returns: the inferred misses run through the boxes
// where a return was lost. What the UGVs plan on should not change: the columns the full scans
// show blocked in their height band stay blocked. With inferred misses never lowering an
// occupied voxel and weighed as weaker evidence elsewhere, 148 of 148 stay (x86-64); the rule
// alone keeps 146 (a voxel hit once, not yet occupied, can still be cleared), the weight alone
// kept 148 on x86-64 but 143 of 147 on aarch64 (fused multiply-adds cast slightly different
// rays), neither 132. Asserted: what holds on both architectures.
TEST(NoReturnBeams, LostReturnsLeaveEveryBoxBlockingTheUgvs) {
  auto lidar = std::make_unique<sim::LidarSimulator>();
  const sim::BoxWorld world = one_box_world();
  NoReturnBeams inference(pattern_of(lidar->pattern()));
  auto full = std::make_unique<Mapper>();
  auto inferred = std::make_unique<Mapper>();
  Rng rng(3);
  std::vector<hal::LidarPoint> kept;
  for (int k = 0; k < 20; ++k) {
    const Pose3 sensor{Vec3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 1.0), Quat::Identity()};
    std::span<const hal::LidarPoint> points, misses;
    lidar->scan(world, sensor, points, misses);
    full->insert_scan(sensor, {TimePoint{}, 8.0F, points, misses});
    kept.clear();
    for (const hal::LidarPoint& p : points)
      if (!rng.bernoulli(0.05)) kept.push_back(p);
    inferred->insert_scan(sensor, inference.complete({TimePoint{}, 8.0F, kept, {}}, sensor, 0.0));
  }
  const auto& g = full->geometry();
  const auto blocked = [&](const Mapper& m, int x, int y) {
    for (double z = 0.15; z < 0.6; z += g.resolution())  // a UGV's height band
      if (m.state(Vec3(g.center_of({x, y, 0}).x(), g.center_of({x, y, 0}).y(), z)) ==
          VoxelState::kOccupied)
        return true;
    return false;
  };
  std::size_t columns = 0, still = 0;
  for (int y = 0; y < g.cells_y(); ++y) {
    for (int x = 0; x < g.cells_x(); ++x) {
      if (!blocked(*full, x, y)) continue;
      ++columns;
      still += blocked(*inferred, x, y);
    }
  }
  ASSERT_GT(columns, 30u);
  EXPECT_GE(static_cast<double>(still), 0.95 * static_cast<double>(columns));
}

// The rule itself, exactly: a box and the ground mapped occupied by full scans, then scans in
// which every return is lost (a black world): the inferred misses through them lower none of
// their voxels. (Kept returns' rays are real misses and may: they graze the box's edge voxels.)
TEST(NoReturnBeams, AnInferredMissNeverLowersAnOccupiedVoxel) {
  auto lidar = std::make_unique<sim::LidarSimulator>();
  const sim::BoxWorld world = one_box_world();
  NoReturnBeams inference(pattern_of(lidar->pattern()));
  auto map = std::make_unique<Mapper>();
  const Pose3 sensor{Vec3(0.2, -0.3, 1.0), Quat::Identity()};
  std::span<const hal::LidarPoint> points, misses;
  lidar->scan(world, sensor, points, misses);
  for (int k = 0; k < 3; ++k)
    map->insert_scan(sensor, {TimePoint{}, 8.0F, points, misses});
  const auto& g = map->geometry();
  std::vector<std::size_t> occupied;
  for (int z = 0; z < g.cells_z(); ++z)
    for (int y = 0; y < g.cells_y(); ++y)
      for (int x = 0; x < g.cells_x(); ++x)
        if (map->state(VoxelIndex{x, y, z}) == VoxelState::kOccupied)
          occupied.push_back(g.index({x, y, z}));
  ASSERT_GT(occupied.size(), 50u);
  for (int k = 0; k < 20; ++k) {
    // The ground out of reach: every beam is inferred, so the mapper's rule alone is tested.
    const hal::LidarScanView none = inference.complete({TimePoint{}, 8.0F, {}, {}}, sensor, -1e9);
    ASSERT_EQ(none.misses.size(), 32u * 1200u);
    map->insert_scan(sensor, none);
  }
  std::size_t kept = 0;
  for (const std::size_t i : occupied) {
    const VoxelIndex v{static_cast<int>(i % static_cast<std::size_t>(g.cells_x())),
                       static_cast<int>(i / static_cast<std::size_t>(g.cells_x()) %
                                        static_cast<std::size_t>(g.cells_y())),
                       static_cast<int>(i / (static_cast<std::size_t>(g.cells_x()) *
                                             static_cast<std::size_t>(g.cells_y())))};
    kept += map->state(v) == VoxelState::kOccupied ? 1U : 0U;
  }
  EXPECT_EQ(kept, occupied.size());
}

// The field world's defect, as the 300-mission run found it: a UAV flying 1.6 m up beside a
// 0.2 m wall (a building's, 1.2 m tall), its LiDAR with 2 cm of range noise and 5 % of its
// returns lost. Each lost return, traced to maximum range as if it had seen nothing, ran through
// the wall and the ground behind it: the wall's inside and its shadow were mapped free, and the
// face, hit by noisy returns split between two voxel rows, was all that kept the UGVs out (in the
// missions it sometimes did not). Two rules close it, each on its own: no miss is inferred for a
// beam aimed at the ground within range (here, without the mapper's rule, 76 voxels inside the
// wall stay free: those of beams above the ground's horizon), and an inferred miss ends at the
// first occupied voxel on its way (Mapper::trace; on its own it keeps the wall whole here).
TEST(NoReturnBeams, LostReturnsAtAWallsFootOpenNoWayThroughIt) {
  sim::BoxWorld world;
  world.boxes.push_back({Vec2(-6.65, 4.5), Vec2(2.15, 0.1), 1.2});  // x -8.8 .. -4.5, y 4.4 .. 4.6
  auto lidar = std::make_unique<sim::LidarSimulator>();
  struct Seen {
    int free_inside = 0, free_shadow = 0, open_columns = 0;
  };
  const auto fly = [&](double ground_z) {
    NoReturnBeams inference(pattern_of(lidar->pattern()));
    auto map = std::make_unique<Mapper>();
    Rng rng(5);
    std::vector<hal::LidarPoint> kept;
    for (int pass = 0; pass < 4; ++pass) {
      for (int k = 0; k < 40; ++k) {  // 0.15 m per scan, back and forth 1.6 m off the wall
        const double x = pass % 2 == 0 ? -3.5 - 0.15 * k : -9.5 + 0.15 * k;
        const Pose3 sensor{Vec3(x, 6.2, 1.6), Quat::Identity()};
        std::span<const hal::LidarPoint> points, misses;
        lidar->scan(world, sensor, points, misses);
        kept.clear();
        for (const hal::LidarPoint& p : points) {
          if (rng.bernoulli(0.05)) continue;
          const double r = Vec3(p.x_m, p.y_m, p.z_m).norm();
          const auto f = static_cast<float>((r + rng.gaussian(0.0, 0.02)) / r);
          kept.push_back({p.x_m * f, p.y_m * f, p.z_m * f});
        }
        map->insert_scan(sensor,
                         inference.complete({TimePoint{}, 8.0F, kept, {}}, sensor, ground_z));
      }
    }
    Seen seen;
    const auto is_free = [&](double x, double y, double z) {
      return map->state(Vec3(x, y, z)) == VoxelState::kFree ? 1 : 0;
    };
    for (double x = -8.45; x < -4.8; x += 0.1) {  // 0.3 m or more from the wall's ends
      for (double z = 0.15; z < 1.1; z += 0.1)
        seen.free_inside += is_free(x, 4.45, z);  // the voxel row wholly inside the wall
      for (double z = 0.15; z < 0.5; z += 0.1)
        seen.free_shadow += is_free(x, 4.35, z);  // behind it, low: no ray gets there
    }
    for (double x = -8.75; x < -4.5; x += 0.1) {  // every column of the wall, both voxel rows
      bool blocked = false;
      for (const double y : {4.45, 4.55})
        for (double z = 0.15; z < 0.7; z += 0.1)  // a UGV's height band
          blocked = blocked || map->state(Vec3(x, y, z)) == VoxelState::kOccupied;
      seen.open_columns += blocked ? 0 : 1;
    }
    return seen;
  };
  for (const double ground : {0.0, -1e9}) {  // both rules; the mapper's alone
    const Seen seen = fly(ground);
    EXPECT_EQ(seen.free_inside, 0) << ground;
    EXPECT_EQ(seen.free_shadow, 0) << ground;
    EXPECT_EQ(seen.open_columns, 0) << ground;
  }
}
