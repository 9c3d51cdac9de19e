// Camera RPE cost per frame: AprilTag detection + pose of two tags in a synthesised frame
// (blur + noise), at the two common camera resolutions, for decimation 1/2 and 1/2 threads.
#include <benchmark/benchmark.h>

#include <array>

#include "colag/hal/linux/tag_pose_estimator.hpp"
#include "tag_scene.hpp"

namespace {
using namespace colag;

void BM_TagDetection(benchmark::State& state) {
  linux_hal::CameraIntrinsics camera;
  camera.width = static_cast<int>(state.range(0));
  camera.height = camera.width == 1280 ? 720 : 480;
  camera.fx = camera.fy = camera.width * 0.78;  // the same 65 deg field of view
  camera.cx = (camera.width - 1) / 2.0;
  camera.cy = (camera.height - 1) / 2.0;
  linux_hal::TagPoseConfig config;
  config.camera = camera;
  config.tag_size_m = 0.2;
  config.decimate = static_cast<float>(state.range(1));
  config.threads = static_cast<int>(state.range(2));
  (void)config.tags.push_back({7, 1, Pose3{}});
  (void)config.tags.push_back({11, 2, Pose3{}});
  linux_hal::TagPoseEstimator rpe(config);
  const std::array<test::TagInScene, 2> tags{
      {{7, test::tag_ahead(2.0, 0.3, 0.2, -0.6, 0.2), 0.2},
       {11, test::tag_ahead(3.0, 0.1, 1.0, 0.7, -0.2), 0.2}}};
  const cv::Mat frame = test::render_tags(camera, tags);
  std::array<hal::RelativePoseDetection, 4> out;
  std::size_t found = 0;
  for (auto _ : state) {
    found = rpe.detect(frame, TimePoint{}, out);
    benchmark::DoNotOptimize(out);
  }
  state.counters["tags_found"] = static_cast<double>(found);
}
BENCHMARK(BM_TagDetection)
    ->ArgNames({"width", "decimate", "threads"})
    ->Args({640, 2, 1})
    ->Args({640, 1, 1})
    ->Args({1280, 2, 1})
    ->Args({1280, 2, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
