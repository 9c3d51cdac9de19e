#pragma once
// Typed, fixed-size readers on a Transport: LatestReader keeps the newest sample (for state
// such as odometry or a plan); QueueReader keeps the last Depth samples in order (for
// streams such as map patches or requests) and counts what it had to drop.
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/platform/transport.hpp"

namespace colag::platform {

template <class Msg>
class LatestReader final : public SampleSink {
 public:
  static constexpr msg::Topic kTopic = msg::MessageTraits<Msg>::kTopic;

  Status attach(Transport& transport, RobotId key = kAnyRobot) {
    return transport.subscribe(kTopic, key, *this);
  }
  bool has_value() const { return updates_ > 0; }
  const Msg& value() const { return value_; }
  TimePoint received_at() const { return received_; }
  std::uint64_t updates() const { return updates_; }
  // Copies the newest sample if it has not been taken yet.
  bool take(Msg& out) {
    if (!fresh_) return false;
    out = value_;
    fresh_ = false;
    return true;
  }

 private:
  void on_sample(msg::Topic, const void* sample, TimePoint received) override {
    value_ = *static_cast<const Msg*>(sample);
    received_ = received;
    fresh_ = true;
    ++updates_;
  }
  Msg value_{};
  TimePoint received_{};
  std::uint64_t updates_ = 0;
  bool fresh_ = false;
};

template <class Msg, std::size_t Depth = limits::kDefaultReaderDepth>
class QueueReader final : public SampleSink {
 public:
  static constexpr msg::Topic kTopic = msg::MessageTraits<Msg>::kTopic;

  Status attach(Transport& transport, RobotId key = kAnyRobot) {
    return transport.subscribe(kTopic, key, *this);
  }
  bool pop(Msg& out) { return queue_.pop_front(out); }
  std::size_t size() const { return queue_.size(); }
  std::uint64_t received() const { return received_; }
  std::uint64_t overflowed() const { return overflowed_; }  // oldest samples dropped

 private:
  void on_sample(msg::Topic, const void* sample, TimePoint) override {
    ++received_;
    if (queue_.push_overwrite(*static_cast<const Msg*>(sample))) ++overflowed_;
  }
  RingBuffer<Msg, Depth> queue_;
  std::uint64_t received_ = 0;
  std::uint64_t overflowed_ = 0;
};

}  // namespace colag::platform
