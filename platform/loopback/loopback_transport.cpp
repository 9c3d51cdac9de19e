#include "colag/platform/loopback_transport.hpp"

#include <algorithm>
#include <cstring>

namespace colag::platform {

static_assert(LoopbackTransport::kParticipants <= 64, "participants are bits of a uint64");

LoopbackTransport::LoopbackTransport(std::uint64_t seed) : rng_(seed) {
  for (std::size_t i = slots_.size(); i-- > 0;)
    (void)free_slots_.push_back(static_cast<std::uint16_t>(i));
  for (std::size_t p = 0; p < ports_.size(); ++p) {
    ports_[p].net = this;
    ports_[p].participant = static_cast<std::uint8_t>(p);
  }
}

void LoopbackTransport::set_faults(const LinkFaults& faults) {
  faults_.fill(faults);
}

void LoopbackTransport::set_faults(msg::Topic topic, const LinkFaults& faults) {
  faults_[index(topic)] = faults;
}

Status LoopbackTransport::subscribe(msg::Topic topic, RobotId key, SampleSink& sink) {
  return subscribe_for(kObserver, topic, key, sink);
}

Status LoopbackTransport::subscribe_for(std::uint8_t participant, msg::Topic topic, RobotId key,
                                        SampleSink& sink) {
  if (index(topic) >= msg::kTopicCount) return {Errc::kInvalidArgument, "unknown topic"};
  if (!subscriptions_.push_back({topic, key, &sink, participant})) {
    return {Errc::kCapacityExceeded, "loopback: too many subscriptions"};
  }
  return Status::ok();
}

void LoopbackTransport::count(msg::Topic topic, std::uint64_t TransportStats::*field,
                              std::uint64_t n) {
  total_.*field += n;
  per_topic_[index(topic)].*field += n;
}

bool LoopbackTransport::schedule(std::uint16_t subscription, std::uint16_t slot,
                                 const LinkFaults& faults) {
  Duration delay = faults.latency;
  if (faults.jitter > Duration::zero()) {
    delay += Duration{
        static_cast<std::int64_t>(rng_.below(static_cast<std::uint64_t>(faults.jitter.count())))};
  }
  if (!deliveries_.push_back({now_ + delay, order_++, subscription, slot})) return false;
  std::push_heap(deliveries_.begin(), deliveries_.end(), later);
  ++slots_[slot].refs;
  return true;
}

Status LoopbackTransport::publish(msg::Topic topic, const void* sample) {
  return publish_from(kObserver, topic, sample);
}

Status LoopbackTransport::publish_from(std::uint8_t participant, msg::Topic topic,
                                       const void* sample) {
  if (index(topic) >= msg::kTopicCount || sample == nullptr) {
    ++total_.rejected;
    return {Errc::kInvalidArgument, "loopback: bad topic or null sample"};
  }
  count(topic, &TransportStats::published);
  const RobotId key = msg::message_key(topic, sample);
  const LinkFaults& faults = faults_[index(topic)];
  const bool per_ugv = msg::topic_info(topic).delivery == msg::Delivery::kPerUgv;

  // What the network carries to each participant (DDS: partitions match, keys do not filter).
  const std::size_t bytes = msg::message_wire_bytes(topic, sample);
  if (participant != kObserver) {
    ++traffic_[participant].samples_out;
    traffic_[participant].bytes_out += bytes;
  }
  std::uint64_t reached = 0;
  for (const Subscription& sub : subscriptions_) {
    if (sub.topic != topic || sub.participant == kObserver || sub.participant == participant)
      continue;
    if (per_ugv && sub.key != kAnyRobot && sub.key != key) continue;
    const std::uint64_t bit = std::uint64_t{1} << sub.participant;
    if ((reached & bit) != 0) continue;
    reached |= bit;
    ++traffic_[sub.participant].samples_in;
    traffic_[sub.participant].bytes_in += bytes;
    traffic_[sub.participant].bytes_in_by_topic[index(topic)] += bytes;
  }

  if (free_slots_.empty()) {
    count(topic, &TransportStats::overflowed);
    return {Errc::kCapacityExceeded, "loopback: too many samples in flight"};
  }
  const std::uint16_t slot = free_slots_.back();
  free_slots_.pop_back();
  Slot& s = slots_[slot];
  std::memcpy(s.bytes.data(), sample, msg::topic_info(topic).size_bytes);
  s.topic = topic;
  s.refs = 0;

  Status result = Status::ok();
  for (std::size_t i = 0; i < subscriptions_.size(); ++i) {
    const Subscription& sub = subscriptions_[i];
    if (sub.topic != topic || (sub.key != kAnyRobot && sub.key != key)) continue;
    if (faults.drop_probability > 0.0 && rng_.bernoulli(faults.drop_probability)) {
      count(topic, &TransportStats::dropped);
      continue;
    }
    const auto sub_index = static_cast<std::uint16_t>(i);
    int copies = 1;
    if (faults.duplicate_probability > 0.0 && rng_.bernoulli(faults.duplicate_probability)) {
      copies = 2;
      count(topic, &TransportStats::duplicated);
    }
    for (int c = 0; c < copies; ++c) {
      if (!schedule(sub_index, slot, faults)) {
        count(topic, &TransportStats::overflowed);
        result = {Errc::kCapacityExceeded, "loopback: too many deliveries pending"};
      }
    }
  }
  if (s.refs == 0) (void)free_slots_.push_back(slot);  // nobody to deliver to
  return result;
}

void LoopbackTransport::poll(TimePoint now) {
  now_ = now;
  while (!deliveries_.empty() && deliveries_.front().due <= now) {
    std::pop_heap(deliveries_.begin(), deliveries_.end(), later);
    const Delivery d = deliveries_.back();
    deliveries_.pop_back();
    Slot& s = slots_[d.slot];
    subscriptions_[d.subscription].sink->on_sample(s.topic, s.bytes.data(), now);
    count(s.topic, &TransportStats::delivered);
    if (--s.refs == 0) (void)free_slots_.push_back(d.slot);
  }
}

}  // namespace colag::platform
