#pragma once
// A Transport for the tasks of one executor lane (a robot simulated beside others, see
// LockstepExecutor): publish() keeps the sample, flush() hands the kept samples to the shared
// transport in the order they were published. Flushing the lanes' outboxes one after the other,
// in lane order, after the lanes ran, publishes what running the lanes one after the other
// would have, in the same order and at the same instant. Subscriptions go straight to the
// shared transport (init only); polling is the pump's job, poll() does nothing here.
//
// A sample the shared transport refuses at flush() is counted (stats().rejected), not reported
// to the publishing task, which was told that its sample was kept.
#include <array>
#include <cstddef>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/platform/transport.hpp"

namespace colag::platform {

class LaneOutbox final : public Transport {
 public:
  explicit LaneOutbox(Transport& shared) : shared_(shared) {}

  Status subscribe(msg::Topic topic, RobotId key, SampleSink& sink) override {
    return shared_.subscribe(topic, key, sink);
  }
  Status publish(msg::Topic topic, const void* sample) override;
  void poll(TimePoint) override {}
  TransportStats stats() const override { return stats_; }
  using Transport::publish;

  // Publishes the kept samples on the shared transport, oldest first, and empties the outbox.
  void flush();
  std::size_t size() const { return kept_.size(); }

 private:
  struct Kept {
    alignas(std::max_align_t) std::array<std::byte, msg::kMaxMessageBytes> bytes{};
    msg::Topic topic{};
  };
  Transport& shared_;
  StaticVector<Kept, limits::kLaneOutboxSamples> kept_;
  TransportStats stats_;
};

}  // namespace colag::platform
