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
#include <optional>
#include <string>

#include "colag/board/program.hpp"
#include "colag/ugv/app/resume_state.hpp"
#include "colag/ugv/app/ugv_board.hpp"
#include "colag/ugv/app/ugv_config.hpp"

using namespace colag;

namespace {

void describe(const ugv::UgvBoardConfig& cfg) {
  const hal::can::BaseConfig& b = cfg.base;
  char base[96];
  switch (b.protocol) {
    case hal::can::BaseProtocol::kColag:
      std::snprintf(base, sizeof base, "colag, ids 0x%x/0x%x/0x%x", b.colag.counts_id,
                    b.colag.speeds_id, b.colag.command_id);
      break;
    case hal::can::BaseProtocol::kOdrive:
      std::snprintf(base, sizeof base, "odrive, nodes %d (left) and %d (right)", b.odrive.left.node,
                    b.odrive.right.node);
      break;
    case hal::can::BaseProtocol::kAgilexV2:
      std::snprintf(base, sizeof base, "agilex_v2");
      break;
  }
  std::printf("ugv_fw: UGV %d, goal (%.2f, %.2f), CAN %s (%s), DDS domain %u\n", cfg.nav.id,
              cfg.nav.goal.x(), cfg.nav.goal.y(), cfg.can_interface.c_str(), base,
              cfg.common.dds_domain);
}

int run(const ugv::UgvBoardConfig& config, const board::ProgramArgs& args) {
  ugv::UgvBoardConfig cfg = config;
  // Started again mid-mission: where it stood, not where the mission started.
  if (!cfg.state_file.empty()) {
    std::string why;
    if (const auto kept = ugv::load_resume_state(cfg.state_file, cfg.state_max_age_s, why)) {
      cfg.nav.has_start_guess = true;
      cfg.nav.start_guess = kept->pose;
      std::printf("ugv_fw: resuming at (%.2f, %.2f, %.2f rad), kept %.0f s ago in %s\n",
                  kept->pose.p.x(), kept->pose.p.y(), kept->pose.yaw_rad, kept->age_s,
                  cfg.state_file.c_str());
    } else if (!why.empty()) {
      std::printf("ugv_fw: not resuming: %s; starting from the configured start guess\n",
                  why.c_str());
    }
  }
  if (args.time_scale != 1.0 && cfg.can_interface != "sim") {
    std::fprintf(stderr,
                 "ugv_fw: --time-scale is for the simulated CAN bus (can.interface: sim)\n");
    return board::kExitUsage;
  }

  // Static storage: the board holds the task's maps (~6 MB), fixed at link time.
  static std::optional<ugv::UgvBoard> storage;
  ugv::UgvBoard& ugv = storage.emplace(cfg, args.time_scale);
  board::print_realtime_setup("ugv_fw", ugv.executor().apply(cfg.common.realtime));
  std::string error;
  if (!ugv.start(error)) {
    std::fprintf(stderr, "ugv_fw: %s\n", error.c_str());
    return board::kExitDevice;
  }
  board::stop_on_signals(ugv.executor());
  const TimePoint now = ugv.executor().clock().now();
  ugv.run(args.seconds > 0.0 ? now + seconds(args.seconds) : TimePoint::max());
  // Motors first.
  const bool stopped = ugv.stop_motors();
  ugv.shutdown_base();
  std::printf("ugv_fw: stopping; motors commanded to zero%s\n",
              stopped ? "" : " (send failed: the controller's command timeout stops them)");
  board::print_task_stats("ugv_fw", ugv.schedule());
  ugv.print_counters("ugv_fw");
  return board::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return board::run_program<ugv::UgvBoardConfig>(
      argc, argv, {"ugv_fw", "--duration", ugv::load_ugv_config, describe, run});
}
