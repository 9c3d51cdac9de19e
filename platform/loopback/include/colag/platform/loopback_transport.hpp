#pragma once
// In-process transport for simulation and tests: every robot of a simulated mission publishes
// into one LoopbackTransport, which plays the radio network between them. Deterministic: a
// sample is delivered at the first poll() at or after its arrival time, in (arrival, publish
// order) order, and every injected fault is drawn from one seeded generator.
#include <array>
#include <cstddef>
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/random.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/platform/transport.hpp"

namespace colag::platform {

// Faults applied independently to each (sample, subscriber) pair, like a lossy radio link.
struct LinkFaults {
  double drop_probability = 0.0;
  Duration latency{};                  // fixed part of the delay
  Duration jitter{};                   // + uniform in [0, jitter): may reorder samples
  double duplicate_probability = 0.0;  // a second copy with its own delay
};

class LoopbackTransport final : public Transport {
 public:
  explicit LoopbackTransport(std::uint64_t seed = 1);

  void set_faults(const LinkFaults& faults);  // every topic
  void set_faults(msg::Topic topic, const LinkFaults& faults);

  Status subscribe(msg::Topic topic, RobotId key, SampleSink& sink) override;
  using Transport::publish;  // the typed overload
  Status publish(msg::Topic topic, const void* sample) override;
  void poll(TimePoint now) override;
  TransportStats stats() const override { return total_; }
  const TransportStats& stats(msg::Topic topic) const { return per_topic_[index(topic)]; }
  std::size_t in_flight() const { return deliveries_.size(); }

 private:
  struct Subscription {
    msg::Topic topic;
    RobotId key;
    SampleSink* sink;
  };
  struct Delivery {
    TimePoint due;
    std::uint64_t order;  // publish order: the tie-break that keeps runs deterministic
    std::uint16_t subscription;
    std::uint16_t slot;
  };
  struct alignas(std::max_align_t) Slot {
    std::array<std::byte, msg::kMaxMessageBytes> bytes;
    msg::Topic topic;
    std::uint16_t refs;
  };

  static std::size_t index(msg::Topic t) { return static_cast<std::size_t>(t); }
  // Heap order for std::push_heap (a max-heap): the earliest delivery ends up on top.
  static bool later(const Delivery& a, const Delivery& b) {
    return a.due != b.due ? a.due > b.due : a.order > b.order;
  }
  bool schedule(std::uint16_t subscription, std::uint16_t slot, const LinkFaults& faults);
  void count(msg::Topic topic, std::uint64_t TransportStats::*field, std::uint64_t n = 1);

  Rng rng_;
  TimePoint now_{};
  std::uint64_t order_ = 0;
  std::array<LinkFaults, msg::kTopicCount> faults_{};
  StaticVector<Subscription, limits::kMaxSubscriptions> subscriptions_;
  std::array<Slot, limits::kLoopbackMaxInFlight> slots_;
  StaticVector<std::uint16_t, limits::kLoopbackMaxInFlight> free_slots_;
  StaticVector<Delivery, limits::kLoopbackMaxDeliveries> deliveries_;  // min-heap on (due, order)
  TransportStats total_;
  std::array<TransportStats, msg::kTopicCount> per_topic_{};
};

}  // namespace colag::platform
