#pragma once
// PX4 as the simulated UAV's flight controller, as the firmware meets it through PX4's agent:
// its commander (modes, arming, acknowledgements) and its offboard behaviour, on top of the
// simulated body. It follows PX4's documented rules: offboard is accepted only while a fresh
// OffboardControlMode stream has been coming for a while; arming only with a mode that flies;
// when the stream stops for longer than COM_OF_LOSS_T it fails safe (COM_OBL_RC_ACT = hold:
// it holds where it is and reports a failsafe); NAV_LAND descends and disarms on the ground.
// Frames: the setpoints it is given are already in the body's frame (ENU): the bridge converts
// from NED, as the firmware's driver converts to it.
#include <cstdint>

#include "colag/common/geometry.hpp"
#include "colag/common/time.hpp"
#include "colag/hal/flight_controller.hpp"

namespace colag::sim {

struct Px4VehicleConfig {
  Duration offboard_loss_timeout = std::chrono::seconds(1);  // COM_OF_LOSS_T
  Duration offboard_stream_needed = std::chrono::milliseconds(500);
  double land_speed_mps = 0.7;  // MPC_LAND_SPEED
  double ground_z_m = 0.0;      // where it touches down (its frame)
  double hold_gain = 1.0;       // 1/s: hold and take-off pull towards their point
  double v_max_mps = 3.0;
};

class Px4Vehicle {
 public:
  // PX4's values (VehicleStatus, VehicleCommandAck).
  static constexpr std::uint8_t kNavPosition = 2, kNavLoiter = 4, kNavOffboard = 14, kNavLand = 18;
  static constexpr std::uint8_t kAccepted = 0, kTemporarilyRejected = 1, kDenied = 2,
                                kUnsupported = 3;

  Px4Vehicle(const Px4VehicleConfig& config, hal::FlightController& body)
      : config_(config), body_(body) {}

  void on_heartbeat(TimePoint now);  // an OffboardControlMode
  void on_setpoint(TimePoint now, const hal::FlightSetpoint& sp);
  // A VehicleCommand: the acknowledgement's result.
  std::uint8_t on_command(TimePoint now, std::uint32_t command, float param1, float param2);
  // Flies the body for this period: `position` is where PX4's estimate puts it.
  void step(TimePoint now, const Vec3& position);
  // A failsafe of its own (a battery, a geofence): it holds and says so.
  void fail_safe(const Vec3& position);
  // A pilot takes over: position mode (it holds where it is), no failsafe.
  void pilot_takes_over(const Vec3& position);

  bool armed() const { return armed_; }
  std::uint8_t nav_state() const { return nav_state_; }
  bool failsafe() const { return failsafe_; }

 private:
  void hold(const Vec3& at);
  bool stream_ready(TimePoint now) const;

  Px4VehicleConfig config_;
  hal::FlightController& body_;
  bool armed_ = false;
  std::uint8_t nav_state_ = kNavLoiter;
  bool failsafe_ = false;
  TimePoint stream_since_ = kNever;  // the current unbroken OffboardControlMode stream
  TimePoint last_heartbeat_ = kNever;
  hal::FlightSetpoint setpoint_;
  bool have_setpoint_ = false;
  Vec3 hold_at_ = Vec3::Zero();
  bool holding_ = false;
};

}  // namespace colag::sim
