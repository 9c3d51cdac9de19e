#include "colag/uav/app/uav_board.hpp"

#include <cstdio>
#include <thread>

namespace colag::uav {

UavBoard::UavBoard(const UavBoardConfig& config, double time_scale)
    : config_(config), executor_(time_scale) {}

// The devices the configuration names: false with `error` saying which failed and why.
bool UavBoard::open_devices(std::string& error) {
  const UavBoardConfig& cfg = config_;
  char text[256];
  if (!cfg.sim_hal && !cfg.px4_hal) {
    error =
        "robot.hal board has the camera alone (run --camera-test to bring it up); a mission needs "
        "robot.hal px4 (PX4, LiDAR-inertial odometry and LiDAR over DDS) or sim (SITL)";
    return false;
  }
  if (cfg.sim_hal || cfg.sim_camera) {
    const std::uint32_t sim_domain = hal::sim::sim_domain_for(cfg.common.dds_domain);
    if (const Status s = sim_link_.emplace().init(sim_domain, hal::sim::SimLink::Side::kUav); !s) {
      std::snprintf(text, sizeof text, "sim link on DDS domain %u: %s (%s)", sim_domain,
                    s.message(), dds_strretcode(sim_link_->last_error()));
      error = text;
      return false;
    }
    hal::sim::SimUavDevices& d = sim_devices_.emplace(*sim_link_);
    camera_ = &d;
    if (cfg.sim_hal) {
      flight_ = &d;
      odometry_ = &d;
      lidar_ = &d;
      return true;
    }
  }
  // robot.hal px4: PX4, the odometry, the LiDAR, the camera.
  if (!px4_.emplace().init(cfg.px4, error)) return false;
  flight_ = &*px4_;
  if (cfg.odometry_from_px4) {
    odometry_ = &*px4_;
  } else {
    if (!ros2_odometry_.emplace(executor_.clock()).init(cfg.odometry, error)) return false;
    odometry_ = &*ros2_odometry_;
  }
  if (!ros2_lidar_.emplace(executor_.clock()).init(cfg.lidar, error)) return false;
  lidar_ = &*ros2_lidar_;
  if (!cfg.sim_camera) {
    linux_hal::CameraRpe& cam = camera_rpe_.emplace(cfg.rpe, cfg.camera, executor_.clock());
    if (const Status s = cam.start(); !s) {
      error = cfg.camera.uri + ": " + s.message();
      return false;
    }
    camera_ = &cam;
  }
  return true;
}

bool UavBoard::start(std::string& error) {
  const UavBoardConfig& cfg = config_;
  char text[256];
  if (!open_devices(error)) return false;

  platform::dds::DdsConfig dds_cfg;
  dds_cfg.domain_id = cfg.common.dds_domain;
  dds_cfg.partition = cfg.common.dds_partition.c_str();
  dds_cfg.security = cfg.common.dds_security;
  // What the UAV sends (a peer that is not the UAV announces none of it).
  dds_cfg
      .publish_only<msg::UavOdometry, msg::RelativePose, msg::MapPatch, msg::SupportPlan,
                    msg::ClockReply, msg::NearbyUgvs, msg::UavClockRequest, msg::UavClockReply>();
  if (const Status s = dds_.init(dds_cfg); !s) {
    std::snprintf(text, sizeof text, "DDS: %s (%s)", s.message(),
                  dds_strretcode(dds_.last_error()));
    error = text;
    return false;
  }

  // The table: the transport first, then the task's loops, all from the UAV's schedule table.
  UavSupervisorConfig uc;
  uc.id = cfg.id;
  uc.flight.separation.min_m = cfg.separation_m;
  uc.peer_timeout = cfg.peer_timeout;
  uc.peer_failsafe = cfg.peer_failsafe;
  uc.lidar_pattern = cfg.lidar_pattern;
  uc.camera_view = cfg.camera_view;
  uc.lidar_mount = cfg.lidar_mount;
  UavSupervisorTask& task =
      task_.emplace(uc, dds_, *odometry_, *lidar_, *camera_, *flight_, &pool_);
  pump_.emplace(dds_);
  Status st = executor_.add(platform::row(*pump_, uc.schedule.transport));
  if (st) st = executor_.add(task.rows());
  if (st && cfg.common.ros2.enabled) {
    if (!ros2_.emplace(task).start(cfg.common.dds_domain, cfg.common.ros2,
                                   uc.schedule.telemetry.period, cfg.common.dds_security, error))
      return false;
    st = executor_.add(platform::row(*ros2_, uc.schedule.telemetry));
  }
  if (st) st = executor_.init();
  if (!st) {
    error = std::string("start-up: ") + st.message();
    return false;
  }
  return true;
}

void UavBoard::run(TimePoint end) {
  executor_.run_until(end);
}

bool UavBoard::land(Duration limit) {
  if (!px4_) return true;
  const hal::Clock& clock = executor_.clock();
  const TimePoint end = clock.now() + limit;
  px4_->land(clock.now());
  while (clock.now() < end) {
    const hal::FlightStatus s = px4_->update(clock.now());
    const auto state = px4_->sequencer().state();
    if (state == hal::px4::OffboardSequencer::State::kLanded) return true;
    if (s.state == msg::UavFlight::kLost) return false;    // a pilot or a failsafe has it
    if (s.fault != msg::FlightFault::kNone) return false;  // NAV_LAND refused or unanswered
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

void UavBoard::print_counters(const char* program) const {
  if (!task_) return;
  std::printf("%s: map patches %llu (%llu bytes), schedules %llu, flight controller lost %llu\n",
              program, static_cast<unsigned long long>(task_->sharer().counters().patches),
              static_cast<unsigned long long>(task_->sharer().counters().bytes),
              static_cast<unsigned long long>(task_->health().schedules),
              static_cast<unsigned long long>(task_->health().flight_lost));
  if (sim_devices_)
    std::printf("%s: malformed sim samples %llu\n", program,
                static_cast<unsigned long long>(sim_devices_->malformed()));
  if (px4_) {
    const hal::px4::Px4Counters& c = px4_->counters();
    std::printf(
        "%s: PX4 setpoints %llu, heartbeats %llu, commands %llu, acks %llu, statuses %llu\n",
        program, static_cast<unsigned long long>(c.setpoints),
        static_cast<unsigned long long>(c.heartbeats), static_cast<unsigned long long>(c.commands),
        static_cast<unsigned long long>(c.acks), static_cast<unsigned long long>(c.statuses));
  }
  if (ros2_lidar_) {
    const hal::ros2::Ros2LidarCounters& c = ros2_lidar_->counters();
    std::printf("%s: LiDAR clouds %llu (%llu malformed), points %llu, kept %llu\n", program,
                static_cast<unsigned long long>(c.clouds),
                static_cast<unsigned long long>(c.malformed),
                static_cast<unsigned long long>(c.points), static_cast<unsigned long long>(c.kept));
  }
  if (ros2_) {
    const UavRos2Counters r = ros2_->counters();
    std::printf("%s: ROS 2 telemetry: %llu messages, %llu write errors, %llu periods skipped\n",
                program, static_cast<unsigned long long>(r.published),
                static_cast<unsigned long long>(r.write_errors),
                static_cast<unsigned long long>(r.skipped));
  }
}

}  // namespace colag::uav
