#pragma once
// The base's side of the UGV's CAN bus, for each protocol the firmware speaks, following each
// device's documented behaviour: what the simulated world and the HIL motor emulator put on the
// bus. It turns the host's commands into wheel-speed targets and the wheels' measured motion
// into the protocol's feedback.
//  - colag: SPEED_COMMAND in (zero after `command_timeout`), ENCODER_COUNTS and WHEEL_SPEEDS out.
//  - odrive: two axes, idle at power-up; closed loop on request (refused while an error is
//    latched); velocity input in closed loop; any frame to an axis feeds its watchdog, which
//    trips after `command_timeout` (axis error WATCHDOG_TIMER_EXPIRED, axis to idle); estop and
//    clear-errors; heartbeat every 100 ms, encoder estimates every step.
//  - agilex_v2: standby (RC mode) at power-up; CAN command mode on request; motion commands in
//    CAN mode, zero after `command_timeout`; system state, motion state and odometry every step.
#include <cstdint>

#include "colag/hal/can/base_config.hpp"
#include "colag/hal/can/diff_drive.hpp"

namespace colag::sim {

class BaseEmulator {
 public:
  BaseEmulator(const hal::can::BaseConfig& config, const hal::can::WheelGeometry& geometry,
               Duration command_timeout);

  // Reads the host's commands on `bus`; the wheel speeds (m/s) the controller drives towards.
  hal::can::WheelPair receive(TimePoint now, hal::CanBus& bus);
  // Sends the feedback due at `now`: the wheels' measured travel over the last step (m) and
  // their speeds (m/s).
  void report(TimePoint now, const hal::can::WheelPair& measured_step_m,
              const hal::can::WheelPair& speeds_mps, hal::CanBus& bus);

  // Fault injection: the device's own fault report (colag: the controller goes silent; odrive:
  // the left axis's motor fails; agilex_v2: its e-stop is pressed). Off again releases the
  // e-stop (a latched ODrive error stays until cleared).
  void set_fault(bool on);
  // Whether it drives the wheels now (closed loop / CAN mode, no fault).
  bool driving() const;

 private:
  struct OdriveAxis {
    hal::can::OdriveAxisConfig config;
    std::uint32_t state = 1;  // idle
    std::uint32_t error = 0;
    float input_turns_per_s = 0.0F;
    TimePoint fed = kNever;
    double pos_turns = 0.0;
  };
  void receive_colag(const hal::CanFrame& f);
  void receive_odrive(const hal::CanFrame& f);
  void receive_agilex(const hal::CanFrame& f);
  hal::can::WheelPair odrive_targets(TimePoint now);

  hal::can::BaseConfig config_;
  hal::can::WheelGeometry geometry_;
  Duration command_timeout_;
  bool fault_ = false;
  hal::can::WheelPair target_;
  TimePoint last_command_ = kNever;
  // colag
  double ticks_left_ = 0.0, ticks_right_ = 0.0;  // fractional
  std::uint8_t alive_counts_ = 0, alive_speeds_ = 0;
  // odrive
  OdriveAxis axes_[2];
  TimePoint last_heartbeat_ = kNever;
  // agilex_v2
  std::uint8_t agilex_mode_ = 0;  // RC / standby
  double agilex_left_mm_ = 0.0, agilex_right_mm_ = 0.0;
  std::uint8_t agilex_count_ = 0;
};

}  // namespace colag::sim
