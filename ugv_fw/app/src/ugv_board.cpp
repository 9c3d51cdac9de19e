#include "colag/ugv/app/ugv_board.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "colag/ugv/app/resume_state.hpp"

namespace colag::ugv {

UgvBoard::UgvBoard(const UgvBoardConfig& config, double time_scale)
    : config_(config), executor_(time_scale) {}

bool UgvBoard::open_can(std::string& error) {
  const UgvBoardConfig& cfg = config_;
  char text[256];
  if (cfg.can_interface == "sim") {
    const std::uint32_t domain = hal::sim::sim_domain_for(cfg.common.dds_domain);
    if (const Status s =
            sim_link_.emplace().init(domain, hal::sim::SimLink::Side::kUgv, cfg.nav.id);
        !s) {
      std::snprintf(text, sizeof text, "sim CAN on DDS domain %u: %s (%s)", domain, s.message(),
                    dds_strretcode(sim_link_->last_error()));
      error = text;
      return false;
    }
    bus_ = &sim_bus_.emplace(*sim_link_, cfg.nav.id);
    return true;
  }
  linux_hal::SocketCanConfig can_cfg;
  can_cfg.interface = cfg.can_interface;
  for (const hal::can::IdFilter& f : hal::can::base_filters(cfg.base))
    (void)can_cfg.filters.push_back({f.id, f.mask, f.extended});
  linux_hal::SocketCanBus& b = socketcan_.emplace(can_cfg, executor_.clock());
  if (const Status s = b.open(); !s) {
    std::snprintf(text, sizeof text, "%s: %s (%s)", cfg.can_interface.c_str(), s.message(),
                  std::strerror(b.driver_stats().last_errno));
    error = text;
    return false;
  }
  bus_ = &b;
  return true;
}

bool UgvBoard::start(std::string& error) {
  const UgvBoardConfig& cfg = config_;
  if (!open_can(error)) return false;
  hal::can::CanBase& base = base_.emplace(*bus_, cfg.base, cfg.wheels);

  platform::dds::DdsConfig dds_cfg;
  dds_cfg.domain_id = cfg.common.dds_domain;
  dds_cfg.partition = cfg.common.dds_partition.c_str();
  dds_cfg.security = cfg.common.dds_security;
  dds_cfg.ugvs = {cfg.nav.id, 1};  // its own partition only: what is for it, and as itself
  dds_cfg
      .publish_only<msg::UgvStatus, msg::CollisionInfo, msg::ClockRequest>();  // what a UGV sends
  if (const Status s = dds_.init(dds_cfg); !s) {
    error = std::string("DDS: ") + s.message();
    (void)stop_motors();
    return false;
  }

  // The table: the transport first, then the task's loops, all from the UGV's schedule table.
  UgvNavTask& task = task_.emplace(cfg.nav, dds_, base.odometry(), base.drive());
  pump_.emplace(dds_);
  Status st = executor_.add(platform::row(*pump_, cfg.nav.schedule.transport));
  if (st) st = executor_.add(task.rows());
  if (st && cfg.common.ros2.enabled) {
    if (!ros2_.emplace(task).start(cfg.common.dds_domain, cfg.common.ros2, cfg.common.dds_security,
                                   error)) {
      (void)stop_motors();
      return false;
    }
    st = executor_.add(platform::row(*ros2_, cfg.nav.schedule.telemetry));
  }
  if (st) st = executor_.init();
  if (!st) {
    error = std::string("start-up: ") + st.message();
    (void)stop_motors();
    return false;
  }
  return true;
}

void UgvBoard::run(TimePoint end) {
  // In one-second slices: between them (on this thread, between the task's steps) the pose is
  // kept for a restart. A slice ends at a release time, so the table's phase is unchanged.
  while (!executor_.stop_requested()) {
    const TimePoint now = executor_.clock().now();
    if (now >= end) break;
    executor_.run_until(std::min(end, now + std::chrono::seconds(1)));
    keep_state();
  }
}

void UgvBoard::keep_state() {
  if (config_.state_file.empty() || !task_ || !task_->estimator().initialized()) return;
  std::string error;
  if (save_resume_state(config_.state_file, task_->estimator().pose(), error)) return;
  if (state_errors_++ == 0) std::fprintf(stderr, "ugv_fw: %s (pose not kept)\n", error.c_str());
}

bool UgvBoard::stop_motors() {
  if (!base_) return true;
  const Status stopped = base_->drive().stop(executor_.clock().now());
  (void)base_->drive().stop(executor_.clock().now());
  return static_cast<bool>(stopped);
}

void UgvBoard::shutdown_base() {
  if (base_) base_->drive().shutdown(executor_.clock().now());
}

void UgvBoard::print_counters(const char* program) const {
  if (bus_ == nullptr || !base_) return;
  const hal::can::BaseCounters c = base_->counters();
  const hal::CanBusStats b = bus_->stats();
  std::printf(
      "%s: CAN (%s) rx %llu, tx %llu, tx failures %llu, bad frames %llu, lost %llu, "
      "implausible %llu, watchdog trips %llu, base faults %llu (%llu cleared by the driver)\n",
      program, hal::can::to_string(config_.base.protocol),
      static_cast<unsigned long long>(b.rx_frames), static_cast<unsigned long long>(b.tx_frames),
      static_cast<unsigned long long>(b.tx_failures), static_cast<unsigned long long>(c.bad_frames),
      static_cast<unsigned long long>(c.lost), static_cast<unsigned long long>(c.implausible),
      static_cast<unsigned long long>(task_ ? task_->health().watchdog_trips : 0),
      static_cast<unsigned long long>(task_ ? task_->health().base_faults : 0),
      static_cast<unsigned long long>(c.recoveries));
  if (ros2_) {
    const UgvRos2Counters r = ros2_->counters();
    std::printf(
        "%s: ROS 2 telemetry: %llu messages, %llu write errors, %llu periods skipped, "
        "%llu goals (%llu refused)\n",
        program, static_cast<unsigned long long>(r.published),
        static_cast<unsigned long long>(r.write_errors), static_cast<unsigned long long>(r.skipped),
        static_cast<unsigned long long>(r.goals), static_cast<unsigned long long>(r.goals_refused));
  }
}

}  // namespace colag::ugv
