#pragma once
// What a UGV's firmware process sees of the network across a restart (FaultConfig::kill_ugv): a
// Transport in front of the robot's own that outlives the process. Its subscriptions reach the
// robot's transport once, through relays; kill() cuts every relay from the dead process's
// readers (what arrives while no process runs is lost, as on a real network), and the next
// process's subscriptions take the relays over, topic and key, in the order it makes them. The
// robot's transport, whose subscriptions are for the life of the mission, never sees a reader
// that no longer exists.
#include <memory>
#include <vector>

#include "colag/platform/transport.hpp"

namespace colag::mission {

class RebootLink final : public platform::Transport {
 public:
  explicit RebootLink(platform::Transport& robot) : robot_(robot) {}

  Status subscribe(msg::Topic topic, RobotId key, platform::SampleSink& sink) override;
  // Refused while no process runs (from kill() to start()).
  Status publish(msg::Topic topic, const void* sample) override;
  void poll(TimePoint now) override { robot_.poll(now); }
  platform::TransportStats stats() const override { return robot_.stats(); }
  using Transport::publish;

  // The process died: nothing reaches its readers and nothing it still holds is sent.
  void kill();
  // The next process starts: its subscriptions take the relays over.
  void start() { alive_ = true; }
  std::size_t relays() const { return relays_.size(); }

 private:
  struct Relay final : platform::SampleSink {
    void on_sample(msg::Topic t, const void* sample, TimePoint received) override {
      if (target != nullptr) target->on_sample(t, sample, received);
    }
    msg::Topic topic{};
    RobotId key = 0;
    platform::SampleSink* target = nullptr;
  };
  platform::Transport& robot_;
  std::vector<std::unique_ptr<Relay>> relays_;  // built at init only; stable addresses
  bool alive_ = true;
};

}  // namespace colag::mission
