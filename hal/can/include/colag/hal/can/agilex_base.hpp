#pragma once
// An AgileX base (protocol V2, chassis level): WheelOdometry from its odometry frames (each
// side's travel), Drive as motion commands (linear and angular speed) sent every control period.
// It selects CAN command mode at start and again while the base reports another mode (the RC
// transmitter can take it over). Its e-stop, its exception state and fault bits, a lost system
// state and bus-off are its health: the task stops on each.
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/hal/can/agilex_protocol.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/drive.hpp"
#include "colag/hal/wheel_odometry.hpp"

namespace colag::hal::can {

struct AgilexConfig {
  int left_sign = 1;  // +1: the base counts the side's forward travel as positive
  int right_sign = 1;
  double max_angular_radps = 2.0;  // the base's own limit on the commanded turn rate
  bool clear_errors_at_start = true;
  Duration state_timeout = std::chrono::milliseconds(300);  // system state is cyclic
  Duration ready_timeout = std::chrono::seconds(2);         // to report CAN mode once selected
  Duration request_period = std::chrono::milliseconds(500);
};

struct AgilexCounters {
  std::uint64_t frames = 0;
  std::uint64_t states = 0;
  std::uint64_t samples = 0;
  std::uint64_t bad_frames = 0;   // known ids with a wrong length
  std::uint64_t lost_states = 0;  // gaps in the system state's counter
  std::uint64_t implausible = 0;
  std::uint64_t overflowed = 0;
  std::uint64_t mode_requests = 0;
};

class AgilexBase final : public WheelOdometry, public Drive {
 public:
  AgilexBase(CanBus& bus, const AgilexConfig& config, const WheelGeometry& geometry)
      : bus_(bus), config_(config), geometry_(geometry) {}

  bool poll(WheelOdometrySample& out) override;
  TimePoint last_sample_time() const override { return last_stamp_; }
  Status command(const DriveCommand& cmd) override;
  Status stop(TimePoint now) override;
  DriveHealth health() const override { return health_; }

  const AgilexCounters& counters() const { return counters_; }

 private:
  void read_bus();
  void keep_in_can_mode(TimePoint now);
  void update_health(TimePoint now);
  Status send_motion(TimePoint now, double v_mps, double omega_radps);

  CanBus& bus_;
  AgilexConfig config_;
  WheelGeometry geometry_;
  agilex::SystemState state_;
  TimePoint heard_ = kNever;
  bool have_odometry_ = false;
  agilex::Odometry last_odometry_;
  TimePoint last_stamp_{};
  TimePoint started_ = kNever;
  TimePoint last_request_ = kNever;
  RingBuffer<WheelOdometrySample, limits::kOdometryBacklog> pending_;
  DriveHealth health_;
  AgilexCounters counters_;
};

}  // namespace colag::hal::can
