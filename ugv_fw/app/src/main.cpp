// ugv_fw: the UGV board program. SocketCAN wheel encoders and motor controller, Cyclone DDS to
// the UAV and the other UGVs, the UgvNavTask under the real-time executor. With
// `can.interface: sim` the CAN bus is colag_world's simulated one over DDS (SITL); everything
// above the bus is the same.
//
//   ugv_fw --config ugv.yaml [--check-config] [--duration SECONDS]
//
// Exit codes: 0 clean stop (SIGINT/SIGTERM or --duration), 1 a device or DDS failed to start,
// 2 a usage or configuration error.
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>

#include "colag/board/program.hpp"
#include "colag/hal/linux/socketcan_bus.hpp"
#include "colag/hal/sim/sim_devices.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/ugv/app/ugv_config.hpp"
#include "colag/ugv/ugv_nav_task.hpp"

using namespace colag;

namespace {

void describe(const ugv::UgvBoardConfig& cfg) {
  std::printf("ugv_fw: UGV %d, goal (%.2f, %.2f), CAN %s (ids 0x%x/0x%x/0x%x), DDS domain %u\n",
              cfg.nav.id, cfg.nav.goal.x(), cfg.nav.goal.y(), cfg.can_interface.c_str(),
              cfg.protocol.counts_id, cfg.protocol.speeds_id, cfg.protocol.command_id,
              cfg.common.dds_domain);
}

int run(const ugv::UgvBoardConfig& cfg, const board::ProgramArgs& args) {
  if (args.time_scale != 1.0 && cfg.can_interface != "sim") {
    std::fprintf(stderr,
                 "ugv_fw: --time-scale is for the simulated CAN bus (can.interface: sim)\n");
    return board::kExitUsage;
  }

  platform::RealtimeExecutor exec(args.time_scale);
  std::optional<linux_hal::SocketCanBus> socketcan;
  std::optional<hal::sim::SimLink> sim_link;
  std::optional<hal::sim::SimCanBus> sim_bus;
  hal::CanBus* bus_ptr = nullptr;
  if (cfg.can_interface == "sim") {
    const std::uint32_t domain = hal::sim::sim_domain_for(cfg.common.dds_domain);
    if (const Status s = sim_link.emplace().init(domain, hal::sim::SimLink::Side::kUgv, cfg.nav.id);
        !s) {
      std::fprintf(stderr, "ugv_fw: sim CAN on DDS domain %u: %s (%s)\n", domain, s.message(),
                   dds_strretcode(sim_link->last_error()));
      return board::kExitDevice;
    }
    bus_ptr = &sim_bus.emplace(*sim_link, cfg.nav.id);
  } else {
    linux_hal::SocketCanConfig can_cfg;
    can_cfg.interface = cfg.can_interface;
    const std::uint32_t mask = cfg.protocol.extended_ids ? 0x1FFFFFFFu : 0x7FFu;
    (void)can_cfg.filters.push_back({cfg.protocol.counts_id, mask, cfg.protocol.extended_ids});
    (void)can_cfg.filters.push_back({cfg.protocol.speeds_id, mask, cfg.protocol.extended_ids});
    linux_hal::SocketCanBus& b = socketcan.emplace(can_cfg, exec.clock());
    if (const Status s = b.open(); !s) {
      std::fprintf(stderr, "ugv_fw: %s: %s (%s)\n", cfg.can_interface.c_str(), s.message(),
                   std::strerror(b.driver_stats().last_errno));
      return board::kExitDevice;
    }
    bus_ptr = &b;
  }
  hal::CanBus& bus = *bus_ptr;
  hal::can::CanWheelOdometry odometry(bus, cfg.protocol, cfg.wheels);
  hal::can::CanDrive drive(bus, cfg.protocol, cfg.wheels);

  platform::dds::DdsTransport dds;
  platform::dds::DdsConfig dds_cfg;
  dds_cfg.domain_id = cfg.common.dds_domain;
  dds_cfg.partition = cfg.common.dds_partition.c_str();
  dds_cfg.security = cfg.common.dds_security;
  dds_cfg.publishes = {};  // a UGV announces only what it sends
  dds_cfg.publishes[static_cast<std::size_t>(msg::Topic::kUgvStatus)] = true;
  dds_cfg.publishes[static_cast<std::size_t>(msg::Topic::kCollisionInfo)] = true;
  if (const Status s = dds.init(dds_cfg); !s) {
    std::fprintf(stderr, "ugv_fw: DDS: %s\n", s.message());
    (void)drive.stop(exec.clock().now());
    return board::kExitDevice;
  }

  // The task holds the robot's maps (~6 MB): static storage, not main's stack, so the footprint
  // is fixed at link time (`size ugv_fw` shows it in .bss) and cannot overflow the stack.
  static std::optional<ugv::UgvNavTask> task_storage;
  ugv::UgvNavTask& task = task_storage.emplace(cfg.nav, dds, odometry, drive);
  platform::TransportPump pump(dds);
  Status st = exec.add({&pump, cfg.control_period, cfg.control_period / 4});
  if (st) st = exec.add({&task.control_loop(), cfg.control_period, cfg.control_period / 4});
  if (st)
    st = exec.add({&task.planning_loop(), cfg.planning_period, cfg.planning_period / 2,
                   cfg.control_period / 2});
  board::print_realtime_setup("ugv_fw", exec.apply(cfg.common.realtime));
  if (st) st = exec.init();
  if (!st) {
    std::fprintf(stderr, "ugv_fw: start-up: %s\n", st.message());
    (void)drive.stop(exec.clock().now());
    return board::kExitDevice;
  }
  board::stop_on_signals(exec);
  const TimePoint end =
      args.seconds > 0.0 ? exec.clock().now() + seconds(args.seconds) : TimePoint::max();
  exec.run_until(end);
  // Motors first: zero speed (sent twice: a single lost frame must not leave them running;
  // the controller's own 200 ms command timeout is the last line).
  const Status stopped = drive.stop(exec.clock().now());
  (void)drive.stop(exec.clock().now());
  std::printf("ugv_fw: stopping; motors commanded to zero%s\n",
              stopped ? "" : " (send failed: the controller's command timeout stops them)");
  board::print_task_stats("ugv_fw", exec.schedule());
  const auto& c = odometry.counters();
  std::printf(
      "ugv_fw: CAN rx %llu, tx %llu, tx failures %llu, bad frames %llu, lost %llu, "
      "watchdog trips %llu\n",
      static_cast<unsigned long long>(bus.stats().rx_frames),
      static_cast<unsigned long long>(bus.stats().tx_frames),
      static_cast<unsigned long long>(bus.stats().tx_failures),
      static_cast<unsigned long long>(c.bad_checksum + c.wrong_dlc + c.unknown_id),
      static_cast<unsigned long long>(c.lost_frames),
      static_cast<unsigned long long>(task.health().watchdog_trips));
  return board::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return board::run_program<ugv::UgvBoardConfig>(
      argc, argv, {"ugv_fw", "--duration", ugv::load_ugv_config, describe, run});
}
