#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <tuple>
#include <vector>

#include "colag/common/random.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/world/lidar_simulator.hpp"
#include "colag/uav/mapper.hpp"
#include "dense_scans.hpp"

using namespace colag;
using namespace colag::uav;
using colag::test::scan_dense_map;

namespace {

std::set<std::tuple<int, int, int>> traversed(const GridGeometry3d& g, const Vec3& a,
                                              const Vec3& b) {
  std::set<std::tuple<int, int, int>> out;
  any_voxel_on_segment(g, a, b, [&](VoxelIndex v) {
    EXPECT_TRUE(out.insert({v.x, v.y, v.z}).second) << "voxel visited twice";
    return false;
  });
  return out;
}

// Distance from the segment to the voxel's box (0 if they meet), by fine sampling.
double segment_to_voxel(const GridGeometry3d& g, const Vec3& a, const Vec3& b, VoxelIndex v) {
  const Vec3 lo = g.center_of(v) - Vec3::Constant(g.resolution() / 2),
             hi = lo + Vec3::Constant(g.resolution());
  double best = 1e9;
  for (int i = 0; i <= 20000; ++i) {
    const Vec3 p = a + (b - a) * (i / 20000.0);
    best = std::min(best, (p - p.cwiseMax(lo).cwiseMin(hi)).norm());
  }
  return best;
}

// A straight flight 1 m up: 12 m at 3 m/s, 10 Hz.
std::vector<Pose3> straight_flight() {
  std::vector<Pose3> poses;
  poses.reserve(40);
  for (int k = 0; k < 40; ++k)
    poses.push_back({Vec3(0.3, 8.0 - 0.3 * k, 1.0), Quat::Identity()});
  return poses;
}

// How map `a` differs from `reference` (two maps of the same scans) in layers [z0, z1).
struct MapDiff {
  std::size_t observed = 0;         // voxels the reference observed
  std::size_t a_observed = 0;       // voxels `a` observed
  std::size_t differ = 0;           // voxels in a different state
  std::size_t occupied_differ = 0;  // occupied in one map only
  std::size_t false_free = 0;       // free in `a` but not in the reference
  double share() const { return static_cast<double>(differ) / static_cast<double>(observed); }
};
MapDiff compare_maps(const Mapper& a, const Mapper& reference, int z0 = 0,
                     int z1 = kWorldGrid3d.cells_z()) {
  const auto& g = a.geometry();
  MapDiff d;
  for (int z = z0; z < z1; ++z) {
    for (int y = 0; y < g.cells_y(); ++y) {
      for (int x = 0; x < g.cells_x(); ++x) {
        const VoxelState sa = a.state(VoxelIndex{x, y, z});
        const VoxelState sr = reference.state(VoxelIndex{x, y, z});
        d.observed += sr != VoxelState::kUnknown;
        d.a_observed += sa != VoxelState::kUnknown;
        d.differ += sa != sr;
        d.occupied_differ += (sa == VoxelState::kOccupied) != (sr == VoxelState::kOccupied);
        d.false_free += sa == VoxelState::kFree && sr != VoxelState::kFree;
      }
    }
  }
  return d;
}

}  // namespace

TEST(VoxelTraversal, VisitsExactlyTheVoxelsASamplerFinds) {
  const GridGeometry3d g(-2.0, -2.0, 0.0, 0.1, 40, 40, 20);
  Rng rng(12);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a(rng.uniform(-1.9, 1.9), rng.uniform(-1.9, 1.9), rng.uniform(0.05, 1.95));
    const Vec3 b(rng.uniform(-1.9, 1.9), rng.uniform(-1.9, 1.9), rng.uniform(0.05, 1.95));
    const auto cells = traversed(g, a, b);
    // Brute force: sample the segment every 0.1 mm.
    std::set<std::tuple<int, int, int>> sampled;
    const int n = static_cast<int>((b - a).norm() / 1e-4) + 2;
    for (int i = 0; i <= n; ++i) {
      const VoxelIndex v = g.voxel_of(a + (b - a) * (static_cast<double>(i) / n));
      sampled.insert({v.x, v.y, v.z});
    }
    for (const auto& s : sampled)
      EXPECT_TRUE(cells.count(s)) << "trial " << trial << ": missed a voxel";
    // Anything more must be a voxel the segment only grazes (closer than the sampling step).
    for (const auto& c : cells) {
      if (sampled.count(c)) continue;
      const auto [x, y, z] = c;
      EXPECT_LT(segment_to_voxel(g, a, b, {x, y, z}), 1e-4) << "trial " << trial;
    }
    EXPECT_TRUE(cells.count({g.voxel_of(a).x, g.voxel_of(a).y, g.voxel_of(a).z}));
    EXPECT_TRUE(cells.count({g.voxel_of(b).x, g.voxel_of(b).y, g.voxel_of(b).z}));
  }
}

TEST(VoxelTraversal, StopsWhereTheSegmentLeavesTheGrid) {
  const GridGeometry3d g(0.0, 0.0, 0.0, 0.1, 10, 10, 10);
  int visited = 0;
  any_voxel_on_segment(g, Vec3(0.05, 0.05, 0.55), Vec3(5.0, 0.05, 0.55), [&](VoxelIndex v) {
    EXPECT_TRUE(g.contains(v));
    ++visited;
    return false;
  });
  EXPECT_EQ(visited, 10);
}

// The mapper traces each half of a scan up to the sensor's voxel row or column this way.
TEST(VoxelTraversal, StopInFrontOfALayerVisitsThePrefixBeforeIt) {
  const GridGeometry3d g(-2.0, -2.0, 0.0, 0.1, 40, 40, 20);
  Rng rng(5);
  int stopped_short = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a(rng.uniform(-1.9, 1.9), rng.uniform(-1.9, 1.9), rng.uniform(0.05, 1.95));
    const Vec3 b(rng.uniform(-1.9, 1.9), rng.uniform(-1.9, 1.9), rng.uniform(0.05, 1.95));
    const VoxelIndex va = g.voxel_of(a), vb = g.voxel_of(b);
    const int axis = trial % 3;
    const auto along = [&](VoxelIndex v) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); };
    std::vector<VoxelIndex> full;
    any_voxel_on_segment(g, a, b, [&](VoxelIndex v) {
      full.push_back(v);
      return false;
    });
    // A layer between the ends (or the one b is in, or a's own: then no stop).
    const int lo = std::min(along(va), along(vb)), hi = std::max(along(va), along(vb));
    const int cell = lo + static_cast<int>(rng.uniform(0.0, 1.0) * (hi - lo + 1));
    std::vector<std::size_t> cut, expected;
    any_voxel_index_on_segment(g, a, b, VoxelLayer{axis, cell}, [&](std::size_t i) {
      cut.push_back(i);
      return false;
    });
    for (const VoxelIndex& v : full) {
      if (along(v) == cell && along(va) != cell) break;
      expected.push_back(g.index(v));
    }
    EXPECT_EQ(cut, expected) << "trial " << trial << " axis " << axis << " cell " << cell;
    stopped_short += cut.size() < full.size();
  }
  EXPECT_GT(stopped_short, 200);  // the layers were mostly in the way
}

TEST(Mapper, ScanOfOneBoxOccupiedFacesFreeFrontUnknownShadow) {
  sim::BoxWorld world;
  world.boxes.push_back({Vec2(3.0, 0.0), Vec2(0.45, 0.45), 0.6});
  auto lidar = std::make_unique<sim::LidarSimulator>();
  auto map = std::make_unique<Mapper>();
  const Pose3 sensor{Vec3(0.02, 0.03, 1.0), Quat::Identity()};
  std::span<const hal::LidarPoint> points, misses;
  lidar->scan(world, sensor, points, misses);
  ASSERT_GT(points.size(), 10000u);
  map->insert_scan(sensor, {TimePoint{}, 8.0F, points, misses});

  // The face towards the sensor and the top are occupied.
  EXPECT_EQ(map->state(Vec3(2.56, 0.0, 0.3)), VoxelState::kOccupied);
  EXPECT_EQ(map->state(Vec3(2.56, 0.3, 0.1)), VoxelState::kOccupied);
  int top = 0;  // the top face (z = 0.6, on a voxel boundary) is hit by two beam rings
  for (double x = 2.6; x < 3.45; x += 0.1) {
    for (double z : {0.55, 0.65})
      top += map->state(Vec3(x, 0.0, z)) == VoxelState::kOccupied;
  }
  EXPECT_GE(top, 2);
  // Free space between the sensor and the box.
  EXPECT_EQ(map->state(Vec3(1.8, 0.0, 0.5)), VoxelState::kFree);
  EXPECT_EQ(map->state(Vec3(2.3, 0.1, 0.25)), VoxelState::kFree);
  // The ground is seen in front of the box, beyond the blind cone.
  EXPECT_EQ(map->state(Vec3(2.3, 0.0, 0.05)), VoxelState::kOccupied);
  // Behind the box, low down: the shadow. Inside the box: never seen either.
  EXPECT_EQ(map->state(Vec3(4.5, 0.0, 0.2)), VoxelState::kUnknown);
  EXPECT_EQ(map->state(Vec3(3.8, 0.0, 0.05)), VoxelState::kUnknown);
  EXPECT_EQ(map->state(Vec3(3.0, 0.0, 0.3)), VoxelState::kUnknown);
  // Right under the sensor: the beams never go steeper than -25.2 deg.
  EXPECT_EQ(map->state(Vec3(0.0, 0.0, 0.05)), VoxelState::kUnknown);
  // Next to the box, the shadow does not reach.
  EXPECT_EQ(map->state(Vec3(4.5, 2.0, 0.2)), VoxelState::kFree);
  EXPECT_EQ(map->counters().scans, 1u);
  EXPECT_EQ(map->counters().rays, points.size() + misses.size());
}

TEST(Mapper, RepeatedMissesClearAnObstacleThatMovedAndHitsComeBack) {
  auto map = std::make_unique<Mapper>();
  const Pose3 sensor{Vec3(0.05, 0.05, 1.05), Quat::Identity()};
  const hal::LidarPoint hit{2.0F, 0.0F, 0.0F};
  const hal::LidarPoint through{4.0F, 0.0F, 0.0F};
  map->insert_scan(sensor, {TimePoint{}, 8.0F, {&hit, 1}, {}});
  EXPECT_EQ(map->state(Vec3(2.05, 0.05, 1.05)), VoxelState::kOccupied);
  // One pass-through does not clear it (0.85 then 0.35: p = 0.75 < 0.8 => free, in fact).
  int scans = 0;
  while (map->state(Vec3(2.05, 0.05, 1.05)) == VoxelState::kOccupied && scans < 10) {
    map->insert_scan(sensor, {TimePoint{}, 8.0F, {&through, 1}, {}});
    ++scans;
  }
  EXPECT_EQ(scans, 1);
  EXPECT_EQ(map->state(Vec3(4.05, 0.05, 1.05)), VoxelState::kOccupied);
  // Clamping: after many misses one hit is not enough, two are (p_min 0.12: -100 units).
  for (int i = 0; i < 20; ++i)
    map->insert_scan(sensor, {TimePoint{}, 8.0F, {&through, 1}, {}});
  map->insert_scan(sensor, {TimePoint{}, 8.0F, {&hit, 1}, {}});
  EXPECT_EQ(map->state(Vec3(2.05, 0.05, 1.05)), VoxelState::kFree);
  map->insert_scan(sensor, {TimePoint{}, 8.0F, {&hit, 1}, {}});
  EXPECT_EQ(map->state(Vec3(2.05, 0.05, 1.05)), VoxelState::kOccupied);
}

// An inferred miss (a beam of the pattern without a return) that crosses a voxel occupied now
// lost its return there, most likely: it lowers the voxels between the sensor and that voxel,
// none behind it (the inside of a wall, its shadow), whichever way the scan is cut.
TEST(Mapper, AnInferredMissEndsAtTheFirstOccupiedVoxelOnItsWay) {
  for (const MapperSplit split : {MapperSplit::kRows, MapperSplit::kColumns}) {
    MapperConfig config;
    config.split = split;
    auto map = std::make_unique<Mapper>(config);
    const Pose3 sensor{Vec3(0.05, 0.05, 1.05), Quat::Identity()};
    // A wall 2 m ahead along x, hit once: occupied. Then beams through it and beyond, inferred.
    const hal::LidarPoint wall{2.0F, 0.0F, 0.0F};
    map->insert_scan(sensor, {TimePoint{}, 8.0F, {&wall, 1}, {}});
    ASSERT_EQ(map->state(Vec3(2.05, 0.05, 1.05)), VoxelState::kOccupied);
    std::vector<hal::LidarPoint> through;
    for (int k = -3; k <= 3; ++k)
      through.push_back({6.0F, 0.01F * static_cast<float>(k), 0.0F});
    hal::LidarScanView inferred{TimePoint{}, 8.0F, {}, through};
    inferred.misses_inferred = true;
    for (int k = 0; k < 30; ++k)
      map->insert_scan(sensor, inferred);
    EXPECT_EQ(map->state(Vec3(2.05, 0.05, 1.05)), VoxelState::kOccupied);
    EXPECT_EQ(map->state(Vec3(1.25, 0.05, 1.05)), VoxelState::kFree);  // in front: seen free
    for (double x = 2.15; x < 6.0; x += 0.1)  // behind: as it was, never observed
      EXPECT_EQ(map->state(Vec3(x, 0.05, 1.05)), VoxelState::kUnknown) << x;
    EXPECT_GT(map->counters().misses_undone, 30u);
    // The same beams as real misses (a listed no-return, not inferred) do clear it.
    hal::LidarScanView listed{TimePoint{}, 8.0F, {}, through};
    map->insert_scan(sensor, listed);
    map->insert_scan(sensor, listed);
    EXPECT_EQ(map->state(Vec3(3.05, 0.05, 1.05)), VoxelState::kFree);
  }
}

TEST(Mapper, IgnoresScansFromOutsideTheGridAndNonFinitePoints) {
  auto map = std::make_unique<Mapper>();
  const hal::LidarPoint bad{std::numeric_limits<float>::quiet_NaN(), 0.0F, 0.0F};
  const hal::LidarPoint ok{1.0F, 0.0F, 0.0F};
  map->insert_scan({Vec3(0, 0, 50), Quat::Identity()}, {TimePoint{}, 8.0F, {&ok, 1}, {}});
  EXPECT_EQ(map->counters().rays_outside, 1u);
  map->insert_scan({Vec3(0, 0, 1), Quat::Identity()}, {TimePoint{}, 8.0F, {&bad, 1}, {}});
  EXPECT_EQ(map->counters().rays_outside, 2u);
  EXPECT_EQ(map->counters().voxel_updates, 0u);
}

// The window moves with the UAV: what both windows hold keeps its state to the voxel, what
// enters is unknown, and a scan from beyond the old edge maps there.
TEST(Mapper, MovedWindowKeepsWhatItHoldsAndMapsBeyondTheOldEdge) {
  auto map = std::make_unique<Mapper>();
  scan_dense_map(straight_flight(), {map.get()});
  const GridGeometry3d before = map->geometry();
  const int nz = 12;  // the layers the flight maps
  std::vector<VoxelState> old(before.layer().size() * nz);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < before.cells_y(); ++y)
      for (int x = 0; x < before.cells_x(); ++x)
        old[before.index({x, y, z})] = map->state(VoxelIndex{x, y, z});
  EXPECT_FALSE(map->move_to(Vec2(-15.05, -20.0)).is_ok());  // off the lattice
  ASSERT_TRUE(map->move_to(Vec2(-15.0, -23.0)).is_ok());    // 5 m east, 3 m south
  const GridGeometry3d& g = map->geometry();
  EXPECT_DOUBLE_EQ(g.origin_x(), -15.0);
  EXPECT_DOUBLE_EQ(g.origin_y(), -23.0);
  std::size_t kept = 0, entered = 0, known = 0;
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < g.cells_y(); ++y) {
      for (int x = 0; x < g.cells_x(); ++x) {
        const VoxelIndex was{x + 50, y - 30, z};  // the same place in the old window
        const VoxelState now = map->state(VoxelIndex{x, y, z});
        if (before.contains(was)) {
          ASSERT_EQ(now, old[before.index(was)]) << x << " " << y << " " << z;
          ++kept;
          known += now != VoxelState::kUnknown;
        } else {
          ASSERT_EQ(now, VoxelState::kUnknown);
          ++entered;
        }
      }
    }
  }
  EXPECT_EQ(entered, std::size_t{nz} * (400 * 400 - 350 * 370));
  EXPECT_GT(known, 100000u);  // the flight's map came along
  EXPECT_GT(kept, entered);
  // 22 m east: outside the first window, inside this one.
  const hal::LidarPoint hit{2.0F, 0.0F, 0.0F};
  map->insert_scan({Vec3(22.05, 0.05, 1.05), Quat::Identity()}, {TimePoint{}, 8.0F, {&hit, 1}, {}});
  EXPECT_EQ(map->state(Vec3(24.05, 0.05, 1.05)), VoxelState::kOccupied);
  EXPECT_EQ(map->state(Vec3(23.05, 0.05, 1.05)), VoxelState::kFree);
}

// The early stop in Mapper::trace skips miss updates that full tracing would make, and nothing
// else: so it may leave voxels less certain (unknown or more occupied), but it must never call a
// voxel free that full tracing does not, and over a flight it must agree almost everywhere.
TEST(Mapper, EarlyStopNeverAddsFreeSpaceAndAgreesWithFullTracing) {
  MapperConfig full_cfg;
  full_cfg.early_stop_voxels = full_cfg.early_stop_crossed = 1 << 30;
  auto fast = std::make_unique<Mapper>();
  auto full = std::make_unique<Mapper>(full_cfg);
  scan_dense_map(straight_flight(), {fast.get(), full.get()});
  const MapDiff d = compare_maps(*fast, *full);
  EXPECT_EQ(d.false_free, 0u);
  RecordProperty("differ_share", std::to_string(d.share()));
  EXPECT_LT(d.share(), 0.03);
  EXPECT_LT(fast->counters().voxel_visits * 3, full->counters().voxel_visits);
}

// Nothing above the ceiling is worth tracing: it stays unknown, the layers below are mapped as
// without a ceiling (up to the merging of rays that now end together at the ceiling), and a
// sensor above the ceiling still maps what it flies through.
TEST(Mapper, CeilingLeavesTheLayersAboveUnknownAndMapsThoseBelowTheSame) {
  MapperConfig capped_cfg;
  capped_cfg.ceiling_m = 1.5;
  auto capped = std::make_unique<Mapper>(capped_cfg);
  auto open = std::make_unique<Mapper>();
  scan_dense_map(straight_flight(), {capped.get(), open.get()});
  EXPECT_EQ(compare_maps(*capped, *open, 15).a_observed, 0u);  // nothing above the ceiling
  const MapDiff below = compare_maps(*capped, *open, 0, 15);
  EXPECT_GT(below.observed, 100000u);
  EXPECT_EQ(below.occupied_differ, 0u);
  EXPECT_LT(below.share(), 0.01);
  EXPECT_LT(capped->counters().voxel_visits, open->counters().voxel_visits);

  // Flying at 2.05 m, above the 1.5 m ceiling: the sensor's own layer is still mapped.
  scan_dense_map({{Vec3(0.3, 0.3, 2.05), Quat::Identity()}}, {capped.get()});
  EXPECT_EQ(capped->state(Vec3(2.3, 0.3, 2.05)), VoxelState::kFree);
  EXPECT_EQ(capped->state(Vec3(2.3, 0.3, 2.25)), VoxelState::kUnknown);
}

// Cutting a scan by the sensor's row or by its column changes only the order in which the rays
// are traced (which decides some early stops), not what is seen: the same obstacles, almost the
// same free space. Flying along y, the default cuts by column.
TEST(Mapper, RowAndColumnCutsMapTheSameObstacles) {
  MapperConfig rows_cfg, columns_cfg;
  rows_cfg.split = MapperSplit::kRows;
  columns_cfg.split = MapperSplit::kColumns;
  auto rows = std::make_unique<Mapper>(rows_cfg);
  auto columns = std::make_unique<Mapper>(columns_cfg);
  auto along = std::make_unique<Mapper>();
  scan_dense_map(straight_flight(), {rows.get(), columns.get(), along.get()});
  const MapDiff d = compare_maps(*columns, *rows);
  EXPECT_GT(d.observed, 100000u);
  EXPECT_EQ(d.occupied_differ, 0u);
  EXPECT_LT(d.share(), 0.01);
  EXPECT_EQ(rows->counters().scans_by_column, 0u);
  EXPECT_EQ(columns->counters().scans_by_column, 40u);
  EXPECT_EQ(along->counters().scans_by_column, 40u);
  EXPECT_EQ(compare_maps(*along, *columns).differ, 0u);
}

// The halves of a scan touch disjoint voxels, so running them on two threads must give the very
// same map as running them one after the other (the wandering flight cuts by rows and columns).
TEST(Mapper, SameMapOnOneThreadAndOnTwo) {
  sim::MapGenConfig gen;
  gen.boxes = 80;
  gen.seed = 3;
  const sim::BoxWorld world = sim::generate_box_world(gen).value();
  auto lidar = std::make_unique<sim::LidarSimulator>();
  platform::WorkerPool pool(1);
  auto one = std::make_unique<Mapper>();
  auto two = std::make_unique<Mapper>(MapperConfig{}, &pool);
  Rng rng(5);
  for (int k = 0; k < 30; ++k) {  // a wandering, slightly tilted flight
    const Pose3 pose{Vec3(rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(0.8, 1.6)),
                     Quat(Eigen::AngleAxisd(rng.uniform(-0.1, 0.1), Vec3::UnitX()) *
                          Eigen::AngleAxisd(rng.uniform(-M_PI, M_PI), Vec3::UnitZ()))};
    std::span<const hal::LidarPoint> points, misses;
    lidar->scan(world, pose, points, misses);
    one->insert_scan(pose, {TimePoint{}, 8.0F, points, misses});
    two->insert_scan(pose, {TimePoint{}, 8.0F, points, misses});
  }
  const auto& g = one->geometry();
  std::size_t differ = 0;
  for (int z = 0; z < g.cells_z(); ++z) {
    for (int y = 0; y < g.cells_y(); ++y) {
      const std::int8_t* a = one->row(y, z);
      const std::int8_t* b = two->row(y, z);
      for (int x = 0; x < g.cells_x(); ++x)
        differ += a[x] != b[x];
    }
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(one->counters().voxel_updates, two->counters().voxel_updates);
  EXPECT_EQ(one->counters().voxel_visits, two->counters().voxel_visits);
  EXPECT_GT(one->counters().rays_resumed, 0u);
  EXPECT_GT(one->counters().scans_by_column, 5u);
  EXPECT_LT(one->counters().scans_by_column, 25u);
}
