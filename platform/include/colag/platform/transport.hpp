#pragma once
// Robot-to-robot messaging as task code sees it: publish a message struct, or read it through a
// LatestReader / QueueReader (readers.hpp). Two implementations: loopback (in-process, with
// seeded fault injection) and Cyclone DDS. Subscriptions are made during init; after that no
// call allocates (in our code; DDS allocates inside its own library).
#include <cstdint>

#include "colag/common/status.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/topics.hpp"
#include "colag/platform/task.hpp"

namespace colag::platform {

// Receives the samples of one subscription; `sample` points to the topic's message struct and
// is valid only during the call.
class SampleSink {
 public:
  virtual void on_sample(msg::Topic topic, const void* sample, TimePoint received) = 0;

 protected:
  ~SampleSink() = default;
};

struct TransportStats {
  std::uint64_t published = 0;
  std::uint64_t delivered = 0;   // sample handed to a sink (one count per sink)
  std::uint64_t dropped = 0;     // lost on the way (injected loss, or reported by DDS)
  std::uint64_t duplicated = 0;  // extra copies injected
  std::uint64_t overflowed = 0;  // no room to hold a sample in flight
  std::uint64_t rejected = 0;    // publish refused (bad argument, writer error)
};

class Transport {
 public:
  virtual ~Transport() = default;

  // Routes samples of `topic` whose key is `key` (kAnyRobot: every key) to `sink`. Init only.
  virtual Status subscribe(msg::Topic topic, RobotId key, SampleSink& sink) = 0;
  // Sends one sample; `sample` must point to the topic's message struct. Never blocks.
  virtual Status publish(msg::Topic topic, const void* sample) = 0;
  // Hands every sample that has arrived by `now` to its sinks, on the caller's thread.
  virtual void poll(TimePoint now) = 0;
  virtual TransportStats stats() const = 0;

  template <class Msg>
  Status publish(const Msg& m) {
    return publish(msg::MessageTraits<Msg>::kTopic, &m);
  }
};

// Runs Transport::poll from an executor table, first in the table so that every task of a tick
// sees the same inbox.
class TransportPump final : public Task {
 public:
  explicit TransportPump(Transport& transport) : transport_(transport) {}
  const char* name() const override { return "transport"; }
  void step(TimePoint now) override { transport_.poll(now); }

 private:
  Transport& transport_;
};

}  // namespace colag::platform
