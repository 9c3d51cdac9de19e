// uav_fw: the UAV board program.
//
//   uav_fw --config uav.yaml [--check-config] [--camera-test SECONDS]
//
// --check-config validates the configuration and the camera calibration it names.
// --camera-test runs the camera RPE device (capture thread, AprilTag detection, pose) and prints
//   each UGV it sees twice a second: the bring-up step for a new camera, calibration or tag set.
// A full mission run also needs the UAV's flight-controller, odometry and LiDAR drivers
// (hal::FlightController, hal::OdometrySource, hal::Lidar); this repository implements them
// only in the simulator so far, and uav_fw says so instead of flying without them.
//
// Exit codes: 0 success, 1 a device failed or is missing, 2 a usage or configuration error.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "colag/board/board_runtime.hpp"
#include "colag/board/uav_board_config.hpp"

using namespace colag;

namespace {

// Prints what the camera sees, at 2 Hz, from the executor like any task.
class CameraReport final : public platform::Task {
 public:
  explicit CameraReport(linux_hal::CameraRpe& camera) : camera_(camera) {}
  const char* name() const override { return "camera_report"; }
  void step(TimePoint) override {
    const std::size_t n = camera_.poll(seen_);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& d = seen_[i];
      std::printf("uav_fw: UGV %d at (%.3f, %.3f, %.3f) m, yaw %.1f deg, sigma %.3f m\n", d.ugv_id,
                  d.ugv_in_uav.p.x(), d.ugv_in_uav.p.y(), d.ugv_in_uav.p.z(),
                  yaw_of(d.ugv_in_uav.q) * 180.0 / M_PI, std::sqrt(d.covariance(0, 0)));
    }
    std::fflush(stdout);
  }

 private:
  linux_hal::CameraRpe& camera_;
  std::array<hal::RelativePoseDetection, limits::kMaxRpeDetectionsPerFrame> seen_{};
};

}  // namespace

int main(int argc, char** argv) {
  board::ProgramArgs args;
  if (!board::parse_program_args(argc, argv, "uav_fw", "--camera-test", args)) return 2;
  board::UavBoardConfig cfg;
  std::string error;
  if (!board::load_uav_config(args.config_path, cfg, error)) {
    std::fprintf(stderr, "uav_fw: %s\n", error.c_str());
    return 2;
  }
  const auto& cam = cfg.rpe.camera;
  std::printf("uav_fw: UAV %d, camera %s %dx%d f=%.1f px (%s), %zu tags of %.3f m, DDS domain %u\n",
              cfg.id, cfg.camera.uri.c_str(), cam.width, cam.height, cam.fx,
              cam.distorted() ? "distorted lens" : "pinhole", cfg.rpe.tags.size(),
              cfg.rpe.tag_size_m, cfg.common.dds_domain);
  if (args.check_only) return 0;
  if (args.seconds < 0.0) {
    std::fprintf(stderr,
                 "uav_fw: no flight-controller, odometry or LiDAR driver for this board yet "
                 "(only simulated ones exist); run --camera-test to bring up the camera\n");
    return 1;
  }

  platform::RealtimeExecutor exec;
  linux_hal::CameraRpe camera(cfg.rpe, cfg.camera, exec.clock());
  if (const Status s = camera.start(); !s) {
    std::fprintf(stderr, "uav_fw: %s: %s\n", cfg.camera.uri.c_str(), s.message());
    return 1;
  }
  CameraReport report(camera);
  (void)exec.add({&report, std::chrono::milliseconds(500), std::chrono::milliseconds(50)});
  board::print_realtime_setup("uav_fw", exec.apply(cfg.common.realtime));
  if (!exec.init()) return 1;
  board::stop_on_signals(exec);
  exec.run_until(exec.clock().now() + seconds(args.seconds));
  camera.stop();
  const linux_hal::CameraStats s = camera.stats();
  const linux_hal::TagPoseCounters c = camera.detector_counters();
  std::printf(
      "uav_fw: %llu frames (%llu read failures), %llu detections, %llu unknown tags, "
      "slowest frame %.1f ms\n",
      static_cast<unsigned long long>(s.frames), static_cast<unsigned long long>(s.read_failures),
      static_cast<unsigned long long>(c.detections),
      static_cast<unsigned long long>(c.unknown_tags),
      static_cast<double>(s.longest_frame_us) / 1000.0);
  return s.frames > 0 ? 0 : 1;
}
