#pragma once
// A differential-drive base on two ODrive axes (CAN Simple, wheel level): WheelOdometry from the
// axes' encoder estimates, Drive as velocity inputs. It brings the axes into closed-loop velocity
// control at start (clearing errors left from the last run if configured), re-requests it while
// an axis idles without an error, feeds the ODrive's watchdog with every velocity input, clears
// the watchdog's trip once this host is live again, and idles the axes at shutdown. An axis
// error, a lost heartbeat, an axis that will not enter closed loop and bus-off are its health:
// the task stops on each.
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/can/odrive_protocol.hpp"
#include "colag/hal/drive.hpp"
#include "colag/hal/wheel_odometry.hpp"

namespace colag::hal::can {

struct OdriveAxisConfig {
  std::uint8_t node = 0;
  int direction = 1;  // +1: positive motor turns drive the robot forward; -1: mirrored motor
};

struct OdriveConfig {
  OdriveAxisConfig left{0, 1};
  OdriveAxisConfig right{1, -1};            // mirrored on the other side, as most bases mount them
  double motor_turns_per_wheel_turn = 1.0;  // the gear ratio (1 for hub motors)
  bool clear_errors_at_start = true;        // errors latched since the last run (e.g. watchdog)
  Duration heartbeat_timeout = std::chrono::milliseconds(350);  // 3 of the 100 ms heartbeats
  Duration ready_timeout = std::chrono::seconds(2);          // to enter closed loop once requested
  Duration request_period = std::chrono::milliseconds(500);  // re-request closed loop
};

// Wheel travel per motor turn (the gear ratio between them).
inline double metres_per_motor_turn(const OdriveConfig& c, const WheelGeometry& g) {
  return g.metres_per_turn() / c.motor_turns_per_wheel_turn;
}

struct OdriveCounters {
  std::uint64_t frames = 0;
  std::uint64_t heartbeats = 0;
  std::uint64_t estimates = 0;
  std::uint64_t samples = 0;
  std::uint64_t bad_frames = 0;   // our nodes' feedback with a wrong length or non-finite value
  std::uint64_t implausible = 0;  // wheel steps beyond the limits, or time not advancing
  std::uint64_t overflowed = 0;   // samples dropped because the task did not poll
  std::uint64_t closed_loop_requests = 0;
  std::uint64_t watchdog_clears = 0;  // watchdog trips cleared after start (this host stalled)
};

class OdriveBase final : public WheelOdometry, public Drive {
 public:
  OdriveBase(CanBus& bus, const OdriveConfig& config, const WheelGeometry& geometry)
      : bus_(bus), config_(config), geometry_(geometry) {
    axes_[0].config = config.left;
    axes_[1].config = config.right;
  }

  // WheelOdometry
  bool poll(WheelOdometrySample& out) override;
  TimePoint last_sample_time() const override { return last_sample_; }
  // Drive
  Status command(const DriveCommand& cmd) override;
  Status stop(TimePoint now) override;
  DriveHealth health() const override { return health_; }
  void shutdown(TimePoint now) override;

  const OdriveCounters& counters() const { return counters_; }

 private:
  struct Axis {
    OdriveAxisConfig config;
    TimePoint heard = kNever;        // last heartbeat
    TimePoint first_heard = kNever;  // first heartbeat of this run
    bool was_ready = false;          // in closed loop without error at least once this run
    odrive::Heartbeat beat;
    bool have_pos = false, fresh = false;
    double pos_turns = 0.0, used_turns = 0.0;  // newest, and the one of the last sample
    TimePoint pos_stamp{};
  };
  void read_bus();
  void on_estimates(Axis& a, const odrive::EncoderEstimates& e, TimePoint stamp);
  void make_sample();
  void keep_in_closed_loop(TimePoint now);  // the start-up sequence, and re-requests
  void update_health(TimePoint now);
  Status send_velocities(TimePoint now, double left_mps, double right_mps);
  Status send(const CanFrame& f, TimePoint now);

  CanBus& bus_;
  OdriveConfig config_;
  WheelGeometry geometry_;
  Axis axes_[2];                // left, right
  TimePoint started_ = kNever;  // first command: the start-up sequence ran
  TimePoint last_request_ = kNever;
  TimePoint last_sample_{};
  bool have_sample_pair_ = false;
  RingBuffer<WheelOdometrySample, limits::kOdometryBacklog> pending_;
  DriveHealth health_{msg::BaseFault::kNone, 0};
  OdriveCounters counters_;
};

}  // namespace colag::hal::can
