// UAV task parts, the real code paths:
//   scan insertion: one simulated VLP-32 scan (32 x 1200 rays, 8 m) of the dense map into the
//                   3-D log-odds grid (and as the field world's LiDAR gives it: noisy returns
//                   only, the misses inferred from the beam pattern);
//   one patch:      cut, classify and encode one UGV's map patch;
//   scheduler:      solve a support schedule with 7, 16 and 64 live requests.
// Targets (issue 4): <= 5 ms, <= 50 us, <= 50 us / 1 ms / 20 ms.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "colag/common/random.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/world/lidar_errors.hpp"
#include "colag/sim/world/lidar_simulator.hpp"
#include "colag/sim/world/world_profile.hpp"
#include "colag/uav/fleet_scheduler.hpp"
#include "colag/uav/map_sharer.hpp"
#include "colag/uav/mapper.hpp"
#include "colag/uav/no_return_beams.hpp"
#include "colag/uav/scheduler.hpp"
#include "colag/uav/time_cost.hpp"

using namespace colag;
using namespace colag::uav;

namespace {

struct Scene {
  Scene() {
    sim::MapGenConfig cfg;
    cfg.boxes = 80;
    world = sim::generate_box_world(cfg).value();
    lidar = std::make_unique<sim::LidarSimulator>();
    map = std::make_unique<Mapper>();
    // Pre-map along a flight so the patch benchmark sees a realistic mix of cells.
    for (double y = 15; y > -15; y -= 1.5)
      insert(Vec3(0.3, y, 1.0));
  }
  void insert(const Vec3& p) {
    const Pose3 pose{p, Quat::Identity()};
    std::span<const hal::LidarPoint> pts, misses;
    lidar->scan(world, pose, pts, misses);
    map->insert_scan(pose, {TimePoint{}, 8.0F, pts, misses});
  }
  sim::BoxWorld world;
  std::unique_ptr<sim::LidarSimulator> lidar;
  std::unique_ptr<Mapper> map;
};

Scene& scene() {
  static Scene s;
  return s;
}

// A flight at 3 m/s (0.3 m between 10 Hz scans) across the dense map, into a fresh map: each
// scan is new ground ahead plus much already seen, as in a mission. state.range(0) = cores.
// `field`: the field world's LiDAR (sim::field_world(), as config/worlds/field.yaml documents:
// 2 cm range noise, 5 % of the returns lost, returns only), the misses inferred from the beam
// pattern as the UAV task does, inside the timing (it is part of each scan's insertion there).
void scan_insertion(benchmark::State& state, bool field) {
  auto& s = scene();
  platform::WorkerPool pool(static_cast<int>(state.range(0)) - 1);
  constexpr int kScans = 60;
  const sim::LidarErrors errors = sim::field_world().lidar;
  std::vector<std::vector<hal::LidarPoint>> points(kScans), misses(kScans);
  std::vector<Pose3> poses;
  for (int k = 0; k < kScans; ++k) {
    poses.push_back({Vec3(0.3, 12.0 - 0.3 * k, 1.0), Quat::Identity()});
    std::span<const hal::LidarPoint> p, m;
    s.lidar->scan(s.world, poses.back(), p, m);
    if (field) {
      points[k].resize(p.size());
      points[k].resize(
          sim::add_lidar_errors(errors, 1, static_cast<std::uint64_t>(k), p, points[k], nullptr));
    } else {
      points[k].assign(p.begin(), p.end());
      misses[k].assign(m.begin(), m.end());
    }
  }
  const sim::LidarPattern& lp = s.lidar->pattern();
  NoReturnBeams no_returns({lp.beams, lp.lowest_elevation_deg, lp.elevation_step_deg, lp.columns});
  auto map = std::make_unique<Mapper>(MapperConfig{}, &pool);
  int k = 0;
  for (auto _ : state) {
    if (k == kScans) {
      state.PauseTiming();
      map = std::make_unique<Mapper>(MapperConfig{}, &pool);
      k = 0;
      state.ResumeTiming();
    }
    const hal::LidarScanView scan{TimePoint{}, 8.0F, points[k], misses[k]};
    map->insert_scan(poses[k], field ? no_returns.complete(scan, poses[k], 0.0) : scan);
    ++k;
  }
  const auto& c = map->counters();
  const double scans = static_cast<double>(c.scans);
  state.counters["rays"] = static_cast<double>(c.rays + c.rays_outside) / scans;
  state.counters["traced"] = static_cast<double>(c.rays - c.rays_merged) / scans;
  state.counters["visits"] = static_cast<double>(c.voxel_visits) / scans;
  state.counters["updates"] = static_cast<double>(c.voxel_updates) / scans;
  state.counters["resumed"] = static_cast<double>(c.rays_resumed) / scans;
}
void BM_ScanInsertion(benchmark::State& state) {
  scan_insertion(state, false);
}
void BM_ScanInsertionField(benchmark::State& state) {
  scan_insertion(state, true);
}
BENCHMARK(BM_ScanInsertion)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ScanInsertionField)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LidarSimulation(benchmark::State& state) {  // the mock, for the simulator's budget
  auto& s = scene();
  platform::WorkerPool pool(static_cast<int>(state.range(0)) - 1);
  sim::LidarSimulator lidar({}, &pool);
  const Pose3 pose{Vec3(0.3, 2.0, 1.0), Quat::Identity()};
  std::span<const hal::LidarPoint> pts, misses;
  for (auto _ : state)
    lidar.scan(s.world, pose, pts, misses);
}
BENCHMARK(BM_LidarSimulation)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OnePatch(benchmark::State& state) {
  auto& s = scene();
  MapSharer sharer;
  msg::MapPatch patch;
  double y = 14.0;
  double ours = 0, original = 0, patches = 0;
  for (auto _ : state) {
    y = y < -14 ? 14.0 : y - 0.37;
    benchmark::DoNotOptimize(sharer.make_patch(*s.map, Vec2(0.0, y), -M_PI / 2, 0.5, patch));
    state.PauseTiming();
    ours += patch.data.count;
    original += static_cast<double>(original_patch_bytes(*s.map, patch, -0.7, 0.7));
    patches += 1;
    state.ResumeTiming();
  }
  // Payload per patch, and the original's message (int32 address lists + header) for the
  // same 5 x 5 x 1.4 m box.
  state.counters["bytes"] = ours / patches;
  state.counters["original_bytes"] = original / patches;
}
BENCHMARK(BM_OnePatch)->Unit(benchmark::kMicrosecond);

void BM_Scheduler(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Rng rng(42);
  std::vector<ScheduleProblem> problems(16);
  for (auto& p : problems) {
    p.n = n;
    std::vector<Vec2> pts(static_cast<std::size_t>(n) + 1);
    for (auto& q : pts)
      q = Vec2(rng.uniform(-13.5, 13.5), rng.uniform(-13.5, 13.5));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        p.travel[i][j] = j == 0 ? 0.0
                                : (i == 0 ? first_leg_time_s(pts[0], Vec2(1, 0), pts[j], {})
                                          : cruise_time_s(pts[i], pts[j], {}));
      }
      p.due[i] = i == 0 ? 1e18 : rng.uniform(5.0, 10.0 * n);
    }
  }
  auto scheduler = std::make_unique<Scheduler>();
  std::size_t k = 0, feasible = 0;
  for (auto _ : state) {
    const ScheduleResult& r = scheduler->solve(problems[k++ % problems.size()]);
    feasible += r.cost.feasible;
    benchmark::DoNotOptimize(r.cost);
  }
  state.counters["feasible"] =
      benchmark::Counter(static_cast<double>(feasible), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_Scheduler)->Arg(7)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

// K UAVs over n stops on a 100 m site, each from its own place (a cold solve: the worst case;
// the exact solver up to 8 stops).
void BM_FleetScheduler(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int vehicles = static_cast<int>(state.range(1));
  Rng rng(43);
  std::vector<std::unique_ptr<FleetProblem>> problems;
  for (int k = 0; k < 8; ++k) {
    auto p = std::make_unique<FleetProblem>();
    p->n = n;
    p->vehicles = vehicles;
    std::vector<Vec2> pts(static_cast<std::size_t>(n) + 1);
    for (auto& q : pts)
      q = Vec2(rng.uniform(-50, 50), rng.uniform(-50, 50));
    for (int i = 1; i <= n; ++i) {
      for (int j = 1; j <= n; ++j)
        p->travel[i][j] = cruise_time_s(pts[i], pts[j], {});
      p->due[i] = rng.uniform(5.0, 10.0 * n / vehicles);
    }
    for (std::size_t v = 0; v < static_cast<std::size_t>(vehicles); ++v) {
      const Vec2 at(rng.uniform(-50, 50), rng.uniform(-50, 50));
      for (int j = 1; j <= n; ++j)
        p->first[v][j] = first_leg_time_s(at, Vec2(1, 0), pts[j], {});
    }
    problems.push_back(std::move(p));
  }
  auto fleet = std::make_unique<FleetScheduler>();
  std::size_t k = 0, feasible = 0;
  for (auto _ : state) {
    const FleetResult& r = fleet->solve(*problems[k++ % problems.size()]);
    feasible += r.cost.feasible;
    benchmark::DoNotOptimize(r.cost);
  }
  state.counters["feasible"] =
      benchmark::Counter(static_cast<double>(feasible), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_FleetScheduler)
    ->Args({8, 2})
    ->Args({8, 4})
    ->Args({32, 3})
    ->Args({64, 4})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
