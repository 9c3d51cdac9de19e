#include "colag/sim/mission/reboot_link.hpp"

namespace colag::mission {

Status RebootLink::subscribe(msg::Topic topic, RobotId key, platform::SampleSink& sink) {
  for (const std::unique_ptr<Relay>& r : relays_) {
    if (r->target == nullptr && r->topic == topic && r->key == key) {
      r->target = &sink;
      return Status::ok();
    }
  }
  auto relay = std::make_unique<Relay>();
  relay->topic = topic;
  relay->key = key;
  relay->target = &sink;
  if (Status s = robot_.subscribe(topic, key, *relay); !s) return s;
  relays_.push_back(std::move(relay));
  return Status::ok();
}

Status RebootLink::publish(msg::Topic topic, const void* sample) {
  if (!alive_) return {Errc::kUnavailable, "the process is dead"};
  return robot_.publish(topic, sample);
}

void RebootLink::kill() {
  alive_ = false;
  for (const std::unique_ptr<Relay>& r : relays_)
    r->target = nullptr;
}

}  // namespace colag::mission
