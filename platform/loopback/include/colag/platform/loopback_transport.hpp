#pragma once
// In-process transport for simulation and tests: every robot of a simulated mission publishes
// into one LoopbackTransport, which plays the radio network between them. Deterministic: a
// sample is delivered at the first poll() at or after its arrival time, in (arrival, publish
// order) order, and every injected fault is drawn from one seeded generator.
//
// Each robot joins through its own port (port(p): a Transport for participant p), so that the
// network knows what reaches which robot, as DDS would carry it: a robot receives every sample
// of a kFleet topic it reads (whatever key its readers filter on: DDS filters keys at the
// reader, after the bytes arrived), and of a kPerUgv topic only those filed under the UGV it
// reads for (its partition). traffic(p) counts those samples and their wire bytes. Subscribing
// on the transport itself is an observer's (the simulator's instruments): not a robot, not
// counted.
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

// What the network carried to one participant.
struct ParticipantTraffic {
  std::uint64_t samples_in = 0;
  std::uint64_t bytes_in = 0;  // CDR bytes (msg::wire_bytes), before injected loss
  std::array<std::uint64_t, msg::kTopicCount> bytes_in_by_topic{};  // bytes_in, by msg::Topic
  std::uint64_t samples_out = 0;
  std::uint64_t bytes_out = 0;
};

class LoopbackTransport final : public Transport {
 public:
  static constexpr std::size_t kParticipants = limits::kMaxRobots;

  explicit LoopbackTransport(std::uint64_t seed = 1);
  LoopbackTransport(const LoopbackTransport&) = delete;
  LoopbackTransport& operator=(const LoopbackTransport&) = delete;

  // Participant p's (p < kParticipants) view of this network: its subscriptions are its own,
  // its samples count as sent by it; poll() does nothing (the pump polls the network).
  Transport& port(std::size_t p) { return ports_[p]; }
  const ParticipantTraffic& traffic(std::size_t p) const { return traffic_[p]; }

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
  static constexpr std::uint8_t kObserver = 0xFF;
  class Port final : public Transport {
   public:
    Status subscribe(msg::Topic topic, RobotId key, SampleSink& sink) override {
      return net->subscribe_for(participant, topic, key, sink);
    }
    using Transport::publish;
    Status publish(msg::Topic topic, const void* sample) override {
      return net->publish_from(participant, topic, sample);
    }
    void poll(TimePoint) override {}
    TransportStats stats() const override { return net->stats(); }
    LoopbackTransport* net = nullptr;
    std::uint8_t participant = 0;
  };
  struct Subscription {
    msg::Topic topic;
    RobotId key;
    SampleSink* sink;
    std::uint8_t participant;  // kObserver: not a robot
  };
  Status subscribe_for(std::uint8_t participant, msg::Topic topic, RobotId key, SampleSink& sink);
  Status publish_from(std::uint8_t participant, msg::Topic topic, const void* sample);
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
  std::array<Port, kParticipants> ports_{};
  std::array<ParticipantTraffic, kParticipants> traffic_{};
};

}  // namespace colag::platform
