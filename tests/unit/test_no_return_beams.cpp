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
  const hal::LidarScanView out = inference.complete({TimePoint{}, 8.0F, points, {}});
  EXPECT_EQ(out.points.size(), points.size());
  EXPECT_EQ(out.misses.size(), misses.size());  // nothing here is closer than the 1 m minimum
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
}

TEST(NoReturnBeams, LeavesAScanWithMissesOrFromAnUnknownPatternAsItIs) {
  const hal::LidarPoint hit{2.0F, 0.0F, 0.0F}, miss{8.0F, 0.0F, 0.0F};
  NoReturnBeams known(LidarBeamPattern{32, -25.2, 1.2, 1200});
  const hal::LidarScanView listed = known.complete({TimePoint{}, 8.0F, {&hit, 1}, {&miss, 1}});
  EXPECT_EQ(listed.misses.size(), 1u);
  NoReturnBeams unknown;  // no pattern: a non-repetitive scanner, or not configured
  EXPECT_FALSE(unknown.knows_pattern());
  EXPECT_TRUE(unknown.complete({TimePoint{}, 8.0F, {&hit, 1}, {}}).misses.empty());
  NoReturnBeams too_big(LidarBeamPattern{1000, -25.2, 1.2, 1200});  // beyond the limits
  EXPECT_FALSE(too_big.knows_pattern());
  // A return between two beams' elevations is not one of this sensor's: counted, not binned.
  const hal::LidarPoint odd{2.0F, 0.0F, static_cast<float>(2.0 * std::tan(0.6 * M_PI / 180.0))};
  const hal::LidarScanView out = known.complete({TimePoint{}, 8.0F, {&odd, 1}, {}});
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
    inferred->insert_scan(sensor, inference.complete({TimePoint{}, 8.0F, kept, {}}));
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
    const hal::LidarScanView none = inference.complete({TimePoint{}, 8.0F, {}, {}});
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
