#pragma once
// Scripted test doubles of every HAL interface, for unit tests of task code only: a test queues
// what the device "measures" and inspects what the task commanded. No heap: fixed queues.
// The simulated world (sim/world/) is a different thing: it computes measurements from physics.
#include <algorithm>
#include <array>
#include <cstddef>

#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/hal/can_bus.hpp"
#include "colag/hal/clock.hpp"
#include "colag/hal/drive.hpp"
#include "colag/hal/flight_controller.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/hal/odometry_source.hpp"
#include "colag/hal/relative_pose_sensor.hpp"
#include "colag/hal/wheel_odometry.hpp"

namespace colag::hal::scripted {

inline constexpr std::size_t kScriptDepth = 64;

class ManualClock final : public Clock {
 public:
  TimePoint now() const override { return now_; }
  void set(TimePoint t) { now_ = t; }
  void advance(Duration d) { now_ += d; }

 private:
  TimePoint now_{};
};

class ScriptedWheelOdometry final : public WheelOdometry {
 public:
  bool poll(WheelOdometrySample& out) override { return queue_.pop_front(out); }
  TimePoint last_sample_time() const override { return last_; }
  // Queues a sample for the task; returns false when the script queue is full.
  bool push(const WheelOdometrySample& s) {
    last_ = std::max(last_, s.stamp);
    return queue_.try_push(s);
  }

 private:
  RingBuffer<WheelOdometrySample, kScriptDepth> queue_;
  TimePoint last_{};
};

class RecordingDrive final : public Drive {
 public:
  Status command(const DriveCommand& cmd) override {
    if (!fail_status_.is_ok()) return fail_status_;
    last_ = cmd;
    ++commands_;
    return Status::ok();
  }
  Status stop(TimePoint now) override {
    last_ = DriveCommand{now, 0.0, 0.0};
    ++stops_;
    return Status::ok();
  }
  DriveHealth health() const override { return health_; }
  void fail_with(Status s) { fail_status_ = s; }
  void report(DriveHealth h) { health_ = h; }  // what the base says about itself
  const DriveCommand& last() const { return last_; }
  std::size_t commands() const { return commands_; }
  std::size_t stops() const { return stops_; }

 private:
  DriveCommand last_{};
  Status fail_status_{};
  DriveHealth health_;
  std::size_t commands_ = 0;
  std::size_t stops_ = 0;
};

class ScriptedCanBus final : public CanBus {
 public:
  Status send(const CanFrame& frame, TimePoint /*deadline*/) override {
    if (!fail_status_.is_ok()) {
      ++stats_.tx_failures;
      return fail_status_;
    }
    sent_.push_overwrite(frame);
    ++stats_.tx_frames;
    return Status::ok();
  }
  bool receive(CanFrame& out) override {
    if (!rx_.pop_front(out)) return false;
    ++stats_.rx_frames;
    return true;
  }
  CanBusStats stats() const override { return stats_; }

  bool inject(const CanFrame& f) { return rx_.try_push(f); }
  void fail_with(Status s) { fail_status_ = s; }
  const RingBuffer<CanFrame, kScriptDepth>& sent() const { return sent_; }

 private:
  RingBuffer<CanFrame, kScriptDepth> rx_;
  RingBuffer<CanFrame, kScriptDepth> sent_;
  CanBusStats stats_{};
  Status fail_status_{};
};

class ScriptedRelativePoseSensor final : public RelativePoseSensor {
 public:
  using Frame = StaticVector<RelativePoseDetection, limits::kMaxRpeDetectionsPerFrame>;

  std::size_t poll(std::span<RelativePoseDetection> out) override {
    Frame frame;
    if (!frames_.pop_front(frame)) return 0;
    const std::size_t n = std::min(out.size(), frame.size());
    std::copy_n(frame.begin(), n, out.begin());
    return n;
  }
  bool push_frame(const Frame& frame) { return frames_.try_push(frame); }

 private:
  RingBuffer<Frame, 8> frames_;
};

class ScriptedLidar final : public Lidar {
 public:
  bool poll(LidarScanView& out) override {
    if (!pending_) return false;
    pending_ = false;
    out = LidarScanView{
        stamp_, max_range_m_, {points_.data(), points_.size()}, {misses_.data(), misses_.size()}};
    return true;
  }
  // Replaces the scan; returns false if it does not fit.
  bool set_scan(TimePoint stamp, float max_range_m, std::span<const LidarPoint> points,
                std::span<const LidarPoint> misses = {}) {
    if (points.size() + misses.size() > limits::kMaxLidarPoints) return false;
    points_.clear();
    misses_.clear();
    for (const auto& p : points)
      (void)points_.push_back(p);
    for (const auto& p : misses)
      (void)misses_.push_back(p);
    stamp_ = stamp;
    max_range_m_ = max_range_m;
    pending_ = true;
    return true;
  }

 private:
  StaticVector<LidarPoint, limits::kMaxLidarPoints> points_;
  StaticVector<LidarPoint, limits::kMaxLidarPoints> misses_;
  TimePoint stamp_{};
  float max_range_m_ = 0.0F;
  bool pending_ = false;
};

class ScriptedOdometrySource final : public OdometrySource {
 public:
  bool poll(UavState& out) override { return queue_.pop_front(out); }
  bool push(const UavState& s) { return queue_.try_push(s); }

 private:
  RingBuffer<UavState, kScriptDepth> queue_;
};

class RecordingFlightController final : public FlightController {
 public:
  Status send_setpoint(const FlightSetpoint& sp) override {
    last_ = sp;
    ++count_;
    return Status::ok();
  }
  FlightStatus update(TimePoint now) override {
    (void)now;
    return status_;
  }
  void land(TimePoint now) override {
    (void)now;
    landing_ = true;
  }
  const FlightSetpoint& last() const { return last_; }
  std::size_t count() const { return count_; }
  // What update() reports from now on.
  void set_status(FlightStatus s) { status_ = s; }
  bool landing() const { return landing_; }

 private:
  FlightSetpoint last_{};
  std::size_t count_ = 0;
  FlightStatus status_{};
  bool landing_ = false;
};

}  // namespace colag::hal::scripted
