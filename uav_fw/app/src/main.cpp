// uav_fw: the UAV board program.
//
//   uav_fw --config uav.yaml [--check-config] [--camera-test SECONDS]
//
// --check-config validates the configuration and the camera calibration it names.
// --camera-test runs the camera RPE device (capture thread, AprilTag detection, pose) and prints
//   each UGV it sees twice a second: the bring-up step for a new camera, calibration or tag set.
// With `robot.hal: sim`, uav_fw runs the mission: the UavSupervisorTask with Cyclone DDS to the
// UGVs and colag_world's simulated flight controller, odometry, LiDAR and camera over the sim
// link (SITL, scripts/sitl.sh). On a board a mission also needs the UAV's flight-controller,
// odometry and LiDAR drivers (hal::FlightController, hal::OdometrySource, hal::Lidar); this
// repository has no such drivers yet, and uav_fw says so instead of flying without them.
//   uav_fw --config uav.yaml      (robot.hal: sim; runs until SIGINT/SIGTERM)
//
// Exit codes: 0 success, 1 a device failed or is missing, 2 a usage or configuration error.
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "colag/board/program.hpp"
#include "colag/hal/sim/sim_devices.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/uav/app/uav_config.hpp"
#include "colag/uav/uav_supervisor_task.hpp"

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

// The mission on the simulated UAV (SITL): the same task table as on a board.
int run_sim_mission(const uav::UavBoardConfig& cfg, double seconds_to_run, double time_scale) {
  platform::RealtimeExecutor exec(time_scale);
  const std::uint32_t sim_domain = hal::sim::sim_domain_for(cfg.common.dds_domain);
  static hal::sim::SimLink link;  // static: the devices and the task refer to it until exit
  if (const Status s = link.init(sim_domain, hal::sim::SimLink::Side::kUav); !s) {
    std::fprintf(stderr, "uav_fw: sim link on DDS domain %u: %s (%s)\n", sim_domain, s.message(),
                 dds_strretcode(link.last_error()));
    return board::kExitDevice;
  }
  static hal::sim::SimUavDevices devices(link);
  platform::dds::DdsTransport dds;
  platform::dds::DdsConfig dds_cfg;
  dds_cfg.domain_id = cfg.common.dds_domain;
  dds_cfg.partition = cfg.common.dds_partition.c_str();
  dds_cfg.security = cfg.common.dds_security;
  dds_cfg.publishes = {};  // the UAV announces only what it sends
  for (msg::Topic t : {msg::Topic::kUavOdometry, msg::Topic::kRelativePose, msg::Topic::kMapPatch,
                       msg::Topic::kSupportPlan})
    dds_cfg.publishes[static_cast<std::size_t>(t)] = true;
  if (const Status s = dds.init(dds_cfg); !s) {
    std::fprintf(stderr, "uav_fw: DDS: %s (%s)\n", s.message(), dds_strretcode(dds.last_error()));
    return board::kExitDevice;
  }
  uav::UavSupervisorConfig uc;
  uc.id = cfg.id;
  platform::WorkerPool pool(1);  // mapping may use a second core
  // The mapper's grids (tens of MB): static storage, like ugv_fw's task.
  static std::optional<uav::UavSupervisorTask> task_storage;
  uav::UavSupervisorTask& task =
      task_storage.emplace(uc, dds, devices, devices, devices, devices, &pool);
  platform::TransportPump pump(dds);
  using std::chrono::milliseconds;
  Status st = exec.add({&pump, milliseconds(10), milliseconds(2)});
  if (st) st = exec.add({&task.control_loop(), milliseconds(20), milliseconds(5)});
  if (st) st = exec.add({&task.mapping_loop(), milliseconds(100), milliseconds(50)});
  if (st) st = exec.add({&task.sharing_loop(), milliseconds(50), milliseconds(10)});
  if (st) st = exec.add({&task.scheduling_loop(), milliseconds(100), milliseconds(20)});
  board::print_realtime_setup("uav_fw", exec.apply(cfg.common.realtime));
  if (st) st = exec.init();
  if (!st) {
    std::fprintf(stderr, "uav_fw: start-up: %s\n", st.message());
    return board::kExitDevice;
  }
  std::printf("uav_fw: mission on the simulated UAV (sim link on DDS domain %u)\n", sim_domain);
  std::fflush(stdout);
  board::stop_on_signals(exec);
  const TimePoint end =
      seconds_to_run > 0.0 ? exec.clock().now() + seconds(seconds_to_run) : TimePoint::max();
  exec.run_until(end);
  std::printf("uav_fw: stopping\n");
  board::print_task_stats("uav_fw", exec.schedule());
  std::printf("uav_fw: map patches %llu (%llu bytes), schedules %llu, malformed sim samples %llu\n",
              static_cast<unsigned long long>(task.sharer().counters().patches),
              static_cast<unsigned long long>(task.sharer().counters().bytes),
              static_cast<unsigned long long>(task.health().schedules),
              static_cast<unsigned long long>(devices.malformed()));
  return board::kExitOk;
}

void describe(const uav::UavBoardConfig& cfg) {
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
  if (cfg.sim_hal) return run_sim_mission(cfg, args.seconds, args.time_scale);
  if (args.time_scale != 1.0) {
    std::fprintf(stderr, "uav_fw: --time-scale is for the simulated HAL (robot.hal: sim)\n");
    return board::kExitUsage;
  }
  if (args.seconds < 0.0) {
    std::fprintf(stderr,
                 "uav_fw: no flight-controller, odometry or LiDAR driver for this board yet "
                 "(only simulated ones exist); run --camera-test to bring up the camera\n");
    return board::kExitDevice;
  }

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
