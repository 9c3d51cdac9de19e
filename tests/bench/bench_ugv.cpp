// UGV task cycles on a dense (80-box) 27 x 27 m map, the real code paths:
//   planning cycle  = A* + shortcutting + trajectory + collision prediction (10 Hz loop, when
//                     it replans; most cycles only predict)
//   prediction only = collision prediction along the current trajectory
//   estimator+control = EKF predict + a delayed RPE update (re-propagation) + pure pursuit (50 Hz)
// Targets (issue 3): planning + prediction <= 1 ms, estimator + control <= 20 us.
#include <benchmark/benchmark.h>

#include <memory>

#include "box_world_map.hpp"
#include "colag/common/planner.hpp"
#include "colag/common/ugv_ekf.hpp"
#include "colag/ugv/collision_predictor.hpp"
#include "colag/ugv/controller.hpp"

using namespace colag;
using namespace colag::ugv;

namespace {

struct DenseScene {
  DenseScene() {
    sim::MapGenConfig cfg;
    cfg.boxes = 80;
    cfg.seed = 1;
    world = generate_box_world(cfg).value();
    map = std::make_unique<MapStore>();
    test::fill_map_from_world(*map, world, -14.4, -17.6, 14.4, 17.6);
  }
  sim::BoxWorld world;
  std::unique_ptr<MapStore> map;
};

DenseScene& scene() {
  static DenseScene s;
  return s;
}

Mat3 covariance_after_drifting() {
  Mat3 P = Mat3::Zero();
  P(0, 0) = P(1, 1) = 0.02;
  P(2, 2) = 0.004;
  return P;
}

void BM_PlanningCycle(benchmark::State& state) {
  auto& s = scene();
  auto planner = std::make_unique<Planner>();
  CollisionPredictor predictor({}, {});
  Path path;
  Trajectory traj;
  Prediction prediction;
  const double lanes[] = {0.0, -2.0, 2.0, -4.0, 4.0, -6.0, 6.0};
  std::size_t k = 0, expansions = 0;
  for (auto _ : state) {
    // Full-length plans from each lane's start: the worst case (later plans are shorter).
    const double x = lanes[k++ % 7];
    const Vec2 start(x, 16.0), goal(x, -16.0);
    if (planner->plan(*s.map, start, goal, {}, path) != PlanResult::kOk)
      state.SkipWithError("no path");
    traj.build(path, 0.5, {});
    predictor.predict_pose({start, -M_PI / 2}, covariance_after_drifting(), traj, 0, *s.map, {},
                           prediction);
    expansions += planner->last_expansions();
    benchmark::DoNotOptimize(prediction.kind);
  }
  state.counters["expansions"] =
      benchmark::Counter(static_cast<double>(expansions), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_PlanningCycle)->Unit(benchmark::kMicrosecond);

void BM_PredictionOnly(benchmark::State& state) {
  auto& s = scene();
  auto planner = std::make_unique<Planner>();
  Path path;
  Trajectory traj;
  planner->plan(*s.map, Vec2(0, 16), Vec2(0, -16), {}, path);
  traj.build(path, 0.5, {});
  CollisionPredictor predictor({}, {});
  Prediction prediction;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t progress = (i += 7) % traj.size();
    predictor.predict_pose({traj[progress].p, traj[progress].yaw_rad}, covariance_after_drifting(),
                           traj, progress, *s.map, {}, prediction);
    benchmark::DoNotOptimize(prediction.kind);
  }
}
BENCHMARK(BM_PredictionOnly)->Unit(benchmark::kMicrosecond);

void BM_EstimatorAndControl(benchmark::State& state) {
  auto& s = scene();
  auto planner = std::make_unique<Planner>();
  Path path;
  Trajectory traj;
  planner->plan(*s.map, Vec2(0, 16), Vec2(0, -16), {}, path);
  traj.build(path, 0.0, {});
  UgvEkfConfig ekf_config;
  ekf_config.start_window_s = 0.0;  // started from the first relative pose
  UgvEkf ekf(ekf_config);
  Mat3 R = Vec3(0.04, 0.04, 0.0025).asDiagonal();
  (void)ekf.update({TimePoint{}, {Vec2(0, 16), -M_PI / 2}, R});
  Controller controller({}, {});
  TimePoint t{};
  for (auto _ : state) {
    t += std::chrono::milliseconds(20);
    (void)ekf.predict(t, 0.5, 0.01);
    // An RPE taken 50 ms ago: updated in the past, re-propagated to now.
    benchmark::DoNotOptimize(ekf.update({t - std::chrono::milliseconds(50), ekf.pose(), R}));
    const ControlOutput out = controller.step(ekf.pose(), traj, 0.02);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_EstimatorAndControl);

}  // namespace

BENCHMARK_MAIN();
