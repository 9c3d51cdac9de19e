#include "colag/uav/app/uav_board.hpp"

#include <cstdio>

namespace colag::uav {

UavBoard::UavBoard(const UavBoardConfig& config, double time_scale)
    : config_(config), executor_(time_scale) {}

bool UavBoard::start(std::string& error) {
  const UavBoardConfig& cfg = config_;
  char text[256];
  if (!cfg.sim_hal) {
    error =
        "no flight-controller, odometry or LiDAR driver for this board yet (only simulated ones "
        "exist); run --camera-test to bring up the camera";
    return false;
  }
  const std::uint32_t sim_domain = hal::sim::sim_domain_for(cfg.common.dds_domain);
  if (const Status s = sim_link_.emplace().init(sim_domain, hal::sim::SimLink::Side::kUav); !s) {
    std::snprintf(text, sizeof text, "sim link on DDS domain %u: %s (%s)", sim_domain, s.message(),
                  dds_strretcode(sim_link_->last_error()));
    error = text;
    return false;
  }
  hal::sim::SimUavDevices& devices = sim_devices_.emplace(*sim_link_);

  platform::dds::DdsConfig dds_cfg;
  dds_cfg.domain_id = cfg.common.dds_domain;
  dds_cfg.partition = cfg.common.dds_partition.c_str();
  dds_cfg.security = cfg.common.dds_security;
  // What the UAV sends (a peer that is not the UAV announces none of it).
  dds_cfg.publish_only<msg::UavOdometry, msg::RelativePose, msg::MapPatch, msg::SupportPlan,
                       msg::ClockReply>();
  if (const Status s = dds_.init(dds_cfg); !s) {
    std::snprintf(text, sizeof text, "DDS: %s (%s)", s.message(),
                  dds_strretcode(dds_.last_error()));
    error = text;
    return false;
  }

  // The table: the transport first, then the task's loops, all from the UAV's schedule table.
  UavSupervisorConfig uc;
  uc.id = cfg.id;
  uc.lidar_pattern = cfg.lidar_pattern;
  uc.camera_view = cfg.camera_view;
  UavSupervisorTask& task = task_.emplace(uc, dds_, devices, devices, devices, devices, &pool_);
  pump_.emplace(dds_);
  Status st = executor_.add(platform::row(*pump_, uc.schedule.transport));
  if (st) st = executor_.add(task.rows());
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

void UavBoard::print_counters(const char* program) const {
  if (!task_ || !sim_devices_) return;
  std::printf("%s: map patches %llu (%llu bytes), schedules %llu, malformed sim samples %llu\n",
              program, static_cast<unsigned long long>(task_->sharer().counters().patches),
              static_cast<unsigned long long>(task_->sharer().counters().bytes),
              static_cast<unsigned long long>(task_->health().schedules),
              static_cast<unsigned long long>(sim_devices_->malformed()));
}

}  // namespace colag::uav
