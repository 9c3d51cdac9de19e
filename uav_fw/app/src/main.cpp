// uav_fw: the UAV board program.
//
//   uav_fw --config uav.yaml [--check-config] [--camera-test SECONDS]
//
// --check-config validates the configuration and the camera calibration it names.
// --camera-test runs the camera RPE device (capture thread, AprilTag detection, pose) and prints
//   each UGV it sees twice a second: the bring-up step for a new camera, calibration or tag set.
// With `robot.hal: px4` or `sim`, uav_fw runs the mission: the UavSupervisorTask with Cyclone
// DDS to the UGVs, on PX4 (through its uXRCE-DDS agent), FAST-LIO's or PX4's odometry, the
// LiDAR's ROS 2 driver and the camera (px4), or on colag_world's simulated devices over the sim
// link (sim: SITL, scripts/sitl.sh). With PX4 it takes off through the offboard protocol and,
// when stopped (SIGINT/SIGTERM or --duration), lands and waits for PX4 to disarm.
//   uav_fw --config uav.yaml      (runs until SIGINT/SIGTERM)
//
// Exit codes: 0 success, 1 a device failed or is missing, 2 a usage or configuration error.
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "colag/board/program.hpp"
#include "colag/hal/linux/camera_rpe.hpp"
#include "colag/uav/app/uav_board.hpp"
#include "colag/uav/app/uav_config.hpp"

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

// The mission (SITL so far: robot.hal sim). The board is static storage: it holds the
// mapper's grids (tens of MB).
int run_mission(const uav::UavBoardConfig& cfg, const board::ProgramArgs& args) {
  static std::optional<uav::UavBoard> storage;
  uav::UavBoard& uav = storage.emplace(cfg, args.time_scale);
  board::print_realtime_setup("uav_fw", uav.executor().apply(cfg.common.realtime));
  std::string error;
  if (!uav.start(error)) {
    std::fprintf(stderr, "uav_fw: %s\n", error.c_str());
    return board::kExitDevice;
  }
  if (cfg.px4_hal) {
    std::printf("uav_fw: mission on PX4 %s (DDS domain %u%s%s), odometry %s, LiDAR %s\n",
                hal::px4::to_string(cfg.px4.release), cfg.px4.dds_domain,
                cfg.px4.ns.empty() ? "" : ", namespace ", cfg.px4.ns.c_str(),
                cfg.odometry_from_px4 ? "from PX4" : cfg.odometry.topic.c_str(),
                cfg.lidar.topic.c_str());
  } else {
    std::printf("uav_fw: mission on the simulated UAV (sim link on DDS domain %u)\n",
                hal::sim::sim_domain_for(cfg.common.dds_domain));
  }
  std::fflush(stdout);
  board::stop_on_signals(uav.executor());
  const TimePoint now = uav.executor().clock().now();
  uav.run(args.seconds > 0.0 ? now + seconds(args.seconds) : TimePoint::max());
  std::printf("uav_fw: stopping\n");
  if (cfg.px4_hal) {
    std::printf("uav_fw: landing\n");
    std::fflush(stdout);
    std::printf(uav.land(std::chrono::seconds(60)) ? "uav_fw: landed and disarmed\n"
                                                   : "uav_fw: not landed by us (see px4: lines)\n");
  }
  board::print_task_stats("uav_fw", uav.schedule());
  uav.print_counters("uav_fw");
  return board::kExitOk;
}

void describe(const uav::UavBoardConfig& cfg) {
  if (cfg.px4_hal) {
    std::printf(
        "uav_fw: UAV %d, PX4 %s on DDS domain %u (topics rt/%s%sfmu/...), odometry %s%s, LiDAR "
        "%s on DDS domain %u, camera %s, DDS domain %u\n",
        cfg.id, hal::px4::to_string(cfg.px4.release), cfg.px4.dds_domain, cfg.px4.ns.c_str(),
        cfg.px4.ns.empty() ? "" : "/", cfg.odometry_from_px4 ? "from PX4" : "from ",
        cfg.odometry_from_px4 ? "" : cfg.odometry.topic.c_str(), cfg.lidar.topic.c_str(),
        cfg.lidar.dds_domain, cfg.camera.uri.c_str(), cfg.common.dds_domain);
    return;
  }
  if (cfg.sim_hal) {
    std::printf("uav_fw: UAV %d, simulated HAL (SITL), DDS domain %u\n", cfg.id,
                cfg.common.dds_domain);
    return;
  }
  const auto& cam = cfg.rpe.camera;
  std::printf("uav_fw: UAV %d, camera %s %dx%d f=%.1f px (%s), %zu tags of %.3f m, DDS domain %u\n",
              cfg.id, cfg.camera.uri.c_str(), cam.width, cam.height, cam.fx,
              cam.distorted() ? "distorted lens" : "pinhole", cfg.rpe.tags.size(),
              cfg.rpe.tag_size_m, cfg.common.dds_domain);
}

int run(const uav::UavBoardConfig& cfg, const board::ProgramArgs& args) {
  if (args.time_scale != 1.0 && !cfg.sim_hal && !cfg.sim_camera) {
    std::fprintf(stderr, "uav_fw: --time-scale is for the simulated world (SITL)\n");
    return board::kExitUsage;
  }
  // The mission, unless --camera-test (robot.hal board: says what a mission needs).
  if (cfg.sim_hal || args.seconds < 0.0) return run_mission(cfg, args);

  platform::RealtimeExecutor exec;
  linux_hal::CameraRpe camera(cfg.rpe, cfg.camera, exec.clock());
  if (const Status s = camera.start(); !s) {
    std::fprintf(stderr, "uav_fw: %s: %s\n", cfg.camera.uri.c_str(), s.message());
    return board::kExitDevice;
  }
  CameraReport report(camera);
  (void)exec.add({&report, std::chrono::milliseconds(500), std::chrono::milliseconds(50)});
  board::print_realtime_setup("uav_fw", exec.apply(cfg.common.realtime));
  if (!exec.init()) return board::kExitDevice;
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
  return s.frames > 0 ? board::kExitOk : board::kExitDevice;
}

}  // namespace

int main(int argc, char** argv) {
  return board::run_program<uav::UavBoardConfig>(
      argc, argv, {"uav_fw", "--camera-test", uav::load_uav_config, describe, run});
}
