#pragma once
// The offboard protocol with PX4, as a pure state machine (no DDS: the driver feeds it what PX4
// said and does what it asks; tests drive it directly).
//
//   kWaitingForPx4 --PX4 heard and a setpoint to fly--> kPriming: stream OffboardControlMode and
//   setpoints for prime_time (PX4 refuses offboard without a fresh stream) --> kModeRequested:
//   DO_SET_MODE(offboard), acknowledged --> kArmRequested: ARM, acknowledged --> kTakingOff until
//   VehicleStatus says armed and offboard --> kInControl.
//   kInControl --status silent, failsafe, another mode, disarmed--> kLost (terminal: the
//   firmware never takes the aircraft back from a pilot or a failsafe action).
//   Any state but kLost --land()--> kLanding: NAV_LAND until acknowledged; landed once disarmed.
// A command refused, or unacknowledged after its retries, ends in kLost with the reason.
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/hal/flight_controller.hpp"

namespace colag::hal::px4 {

// MAVLink command ids and values PX4 uses in VehicleCommand.
inline constexpr std::uint32_t kCmdNavLand = 21;
inline constexpr std::uint32_t kCmdDoSetMode = 176;
inline constexpr std::uint32_t kCmdArmDisarm = 400;
inline constexpr float kModeCustom = 1.0F;        // DO_SET_MODE param1: custom mode enabled
inline constexpr float kMainModeOffboard = 6.0F;  // DO_SET_MODE param2
inline constexpr std::uint8_t kArmingStateArmed = 2;
inline constexpr std::uint8_t kNavStateOffboard = 14;
// VehicleCommandAck results.
inline constexpr std::uint8_t kAckAccepted = 0;
inline constexpr std::uint8_t kAckTemporarilyRejected = 1;
inline constexpr std::uint8_t kAckInProgress = 5;

struct OffboardConfig {
  Duration prime_time = std::chrono::seconds(1);  // stream before asking for offboard
  // Nothing at all from PX4 (its odometry alone comes at 50-100 Hz): short, so that the UGVs
  // stand still within a second of losing it (this, one UAV sample, their braking ~0.5 s).
  Duration silence_timeout = std::chrono::milliseconds(300);
  Duration status_timeout = std::chrono::seconds(2);  // no VehicleStatus
  Duration ack_timeout = std::chrono::seconds(1);
  int command_attempts = 5;                            // per command, counting the first
  Duration confirm_timeout = std::chrono::seconds(5);  // accepted, but status never shows it
  Duration setpoint_timeout = std::chrono::milliseconds(500);  // no setpoint: stop streaming
};

// What VehicleStatus says, in the fields the protocol needs.
struct Px4Status {
  bool armed = false;
  std::uint8_t nav_state = 0;
  bool failsafe = false;
};

// A command for the driver to send now.
struct Px4Command {
  std::uint32_t command = 0;
  float param1 = 0.0F;
  float param2 = 0.0F;
};

class OffboardSequencer {
 public:
  enum class State : std::uint8_t {
    kWaitingForPx4,
    kPriming,
    kModeRequested,
    kArmRequested,
    kTakingOff,
    kInControl,
    kLanding,
    kLanded,
    kLost,
  };

  explicit OffboardSequencer(const OffboardConfig& config = {}) : config_(config) {}

  // What PX4 said (any message counts as hearing it; status and acks also feed the protocol).
  void heard(TimePoint now) { last_heard_ = now; }
  void on_status(TimePoint now, const Px4Status& s);
  void on_ack(TimePoint now, std::uint32_t command, std::uint8_t result);
  // The firmware has a setpoint to fly (a take-off needs one before offboard is asked for).
  void on_setpoint(TimePoint now) { last_setpoint_ = now; }
  void land(TimePoint now);
  // Set by the driver when the bus shows the other release's topics: reported while waiting.
  void set_wrong_release(bool wrong) { wrong_release_ = wrong; }

  // Advances the protocol. `command` is set (and true returned) when a command is due now.
  bool step(TimePoint now, Px4Command& command);

  // Whether OffboardControlMode and setpoints are to be streamed now.
  bool streaming(TimePoint now) const;
  FlightStatus status() const;
  State state() const { return state_; }
  const Px4Status& last_status() const { return status_; }

 private:
  void lose(msg::FlightFault why);
  void request(TimePoint now, State next, const Px4Command& c);
  bool retry_due(TimePoint now) const;

  OffboardConfig config_;
  State state_ = State::kWaitingForPx4;
  msg::FlightFault fault_ = msg::FlightFault::kNone;
  Px4Status status_;
  TimePoint last_heard_ = kNever;
  TimePoint last_status_ = kNever;
  TimePoint last_setpoint_ = kNever;
  TimePoint started_ = kNever;  // first step
  TimePoint entered_ = kNever;  // when the current state began
  Px4Command pending_;          // the command awaiting its acknowledgement
  TimePoint sent_at_ = kNever;
  int attempts_ = 0;
  bool acked_ = false;
  bool send_now_ = false;
  bool ever_armed_ = false;
  bool wrong_release_ = false;
};

}  // namespace colag::hal::px4
