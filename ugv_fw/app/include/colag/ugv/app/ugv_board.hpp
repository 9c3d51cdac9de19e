#pragma once
// The UGV board program's composition (its topology): the CAN bus the configuration names
// (SocketCAN, or colag_world's simulated bus over DDS in SITL), the wheel drivers on it, the DDS
// transport, the UGV task, and the executor table built from the UGV's schedule table
// (UgvSchedule). ugv_fw's main runs it; tests build it the same way. It holds the task and its
// maps (~6 MB): the program keeps it in static storage, so the footprint is fixed at link time
// (`size ugv_fw` shows it in .bss) and cannot overflow a stack.
#include <cstdint>
#include <optional>
#include <string>

#include "colag/hal/can/can_base.hpp"
#include "colag/hal/linux/socketcan_bus.hpp"
#include "colag/hal/sim/sim_devices.hpp"
#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/realtime_executor.hpp"
#include "colag/ugv/app/ugv_config.hpp"
#include "colag/ugv/app/ugv_ros2_bridge.hpp"
#include "colag/ugv/ugv_nav_task.hpp"

namespace colag::ugv {

class UgvBoard {
 public:
  // `time_scale` != 1 only with the simulated CAN bus (SITL).
  UgvBoard(const UgvBoardConfig& config, double time_scale);
  UgvBoard(const UgvBoard&) = delete;
  UgvBoard& operator=(const UgvBoard&) = delete;

  // Opens the CAN bus and DDS, builds the task and the table, calls every task's init. False
  // with `error` saying which device failed and why (the motors are then commanded to zero).
  bool start(std::string& error);
  // Runs until `end` or a stop request (stop_on_signals).
  void run(TimePoint end);
  // Motors to zero (sent twice: one lost frame must not leave them running; the controller's own
  // command timeout is the last line). False when the frames could not be sent.
  bool stop_motors();
  // The program ends: motors to zero, then the base left safe unattended (ODrive axes idle).
  void shutdown_base();
  // One line of CAN and odometry counters, for the log at exit.
  void print_counters(const char* program) const;

  platform::RealtimeExecutor& executor() { return executor_; }
  const platform::Schedule& schedule() const { return executor_.schedule(); }

 private:
  bool open_can(std::string& error);
  void keep_state();  // its pose to the state file, if one is configured

  UgvBoardConfig config_;
  platform::RealtimeExecutor executor_;
  std::optional<linux_hal::SocketCanBus> socketcan_;
  std::optional<hal::sim::SimLink> sim_link_;
  std::optional<hal::sim::SimCanBus> sim_bus_;
  hal::CanBus* bus_ = nullptr;
  std::optional<hal::can::CanBase> base_;  // the wheels: odometry and drive
  platform::dds::DdsTransport dds_;
  std::optional<platform::TransportPump> pump_;
  std::optional<UgvNavTask> task_;
  std::optional<UgvRos2Bridge> ros2_;  // with `ros2.enabled`
  std::uint64_t state_errors_ = 0;
};

}  // namespace colag::ugv
