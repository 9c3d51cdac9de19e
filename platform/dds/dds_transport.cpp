#include "colag/platform/dds/dds_transport.hpp"

#include "colag/platform/dds/convert.hpp"
#include "colag/platform/dds/dds_security.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

namespace colag::platform::dds {

namespace {
constexpr std::uint32_t kTakeBatch = 16;
std::size_t index(msg::Topic t) {
  return static_cast<std::size_t>(t);
}
}  // namespace

DdsTransport::~DdsTransport() {
  if (writer_.joinable()) {
    stopping_.store(true);
    out_pending_.release();  // wake the writer: it writes what is queued, then stops
    writer_.join();
  }
  if (participant_ > 0) dds_delete(participant_);
}

Status DdsTransport::fail(dds_return_t rc, const char* what) {
  last_error_ = rc;
  return {Errc::kUnavailable, what};
}

dds_qos_t* DdsTransport::make_qos(const msg::TopicInfo& info) const {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos,
                       info.reliability == msg::Reliability::kReliable
                           ? DDS_RELIABILITY_RELIABLE
                           : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, info.history_depth);
  if (info.deadline > Duration::zero()) dds_qset_deadline(qos, info.deadline.count());
  if (config_.partition != nullptr && config_.partition[0] != '\0') {
    dds_qset_partition1(qos, config_.partition);
  }
  return qos;
}

Status DdsTransport::init(const DdsConfig& config) {
  if (participant_ > 0) return {Errc::kInvalidArgument, "DDS transport initialised twice"};
  config_ = config;
  ParticipantQos pqos;
  if (Status s = pqos.init(config_.security); !s) return s;
  participant_ = dds_create_participant(config.domain_id, pqos.get(), nullptr);
  if (participant_ < 0) {
    return fail(participant_, config_.security.enabled()
                                  ? "dds_create_participant failed (security: identity, "
                                    "permissions or governance rejected?)"
                                  : "dds_create_participant failed");
  }

  for (const msg::TopicInfo& info : msg::kTopicTable) {
    const std::size_t i = index(info.topic);
    dds_qos_t* qos = make_qos(info);
    topics_[i] = msg::visit_message_type(info.topic, [&]<class Msg>() {
      return dds_create_topic(participant_, &descriptor<Msg>(), info.name, qos, nullptr);
    });
    if (topics_[i] < 0) {
      dds_delete_qos(qos);
      return fail(topics_[i], "dds_create_topic failed");
    }
    if (config.publishes[i]) {
      writers_[i] = dds_create_writer(participant_, topics_[i], qos, nullptr);
      if (writers_[i] < 0) {
        dds_delete_qos(qos);
        return fail(writers_[i], "dds_create_writer failed");
      }
    }
    dds_delete_qos(qos);
  }
  writer_ = std::thread([this] { writer_loop(); });
  return Status::ok();
}

Status DdsTransport::subscribe(msg::Topic topic, RobotId key, SampleSink& sink) {
  if (participant_ <= 0) return {Errc::kNotReady, "DDS transport not initialised"};
  if (index(topic) >= msg::kTopicCount) return {Errc::kInvalidArgument, "unknown topic"};
  const std::size_t i = index(topic);
  if (readers_[i] == 0) {
    dds_qos_t* qos = make_qos(msg::topic_info(topic));
    readers_[i] = dds_create_reader(participant_, topics_[i], qos, nullptr);
    dds_delete_qos(qos);
    if (readers_[i] < 0) {
      const dds_return_t rc = readers_[i];
      readers_[i] = 0;
      return fail(rc, "dds_create_reader failed");
    }
  }
  if (!subscriptions_.push_back({topic, key, &sink})) {
    return {Errc::kCapacityExceeded, "DDS transport: too many subscriptions"};
  }
  return Status::ok();
}

template <class Msg>
Status DdsTransport::write(dds_entity_t writer, const void* sample) {
  IdlSample<Msg> idl;
  to_idl(*static_cast<const Msg*>(sample), idl);
  const dds_return_t rc = dds_write(writer, &idl.sample);
  if (rc != DDS_RETCODE_OK) return {Errc::kUnavailable, "dds_write failed"};  // the writer thread
  return Status::ok();
}

Status DdsTransport::publish(msg::Topic topic, const void* sample) {
  const std::size_t i = index(topic);
  if (i >= msg::kTopicCount || sample == nullptr || writers_[i] <= 0) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    return {Errc::kInvalidArgument, "DDS transport: no writer for this topic"};
  }
  {
    const std::lock_guard<std::mutex> lock(out_mutex_);
    if (out_size_ == outbox_.size()) {
      overflowed_.fetch_add(1, std::memory_order_relaxed);
      return {Errc::kCapacityExceeded, "DDS transport: outbox full (the writer is behind)"};
    }
    Outgoing& slot = outbox_[(out_head_ + out_size_) % outbox_.size()];
    slot.topic = topic;
    std::memcpy(slot.bytes.data(), sample, msg::topic_info(topic).size_bytes);
    ++out_size_;
    queued_.fetch_add(1, std::memory_order_relaxed);
  }
  out_pending_.release();
  return Status::ok();
}

void DdsTransport::writer_loop() {
  Outgoing out;  // the writer's own copy: dds_write runs outside the mutex
  for (;;) {
    out_pending_.acquire();
    {
      const std::lock_guard<std::mutex> lock(out_mutex_);
      if (out_size_ == 0) {
        if (stopping_.load()) return;
        continue;  // the wake-up to stop, with samples still to write first
      }
      out = outbox_[out_head_];
      out_head_ = (out_head_ + 1) % outbox_.size();
      --out_size_;
    }
    const std::size_t i = index(out.topic);
    const Status s = msg::visit_message_type(
        out.topic, [&]<class Msg>() { return write<Msg>(writers_[i], out.bytes.data()); });
    (s ? written_ : write_failed_).fetch_add(1, std::memory_order_relaxed);
    handled_.fetch_add(1, std::memory_order_release);
    if (stopping_.load()) out_pending_.release();  // keep draining until the outbox is empty
  }
}

void DdsTransport::flush() {
  const std::uint64_t target = queued_.load(std::memory_order_relaxed);
  while (writer_.joinable() && handled_.load(std::memory_order_acquire) < target)
    std::this_thread::sleep_for(std::chrono::microseconds(100));
}

DdsStats DdsTransport::dds_stats() const {
  DdsStats s = stats_;
  s.transport.published = written_.load(std::memory_order_relaxed);
  s.transport.rejected =
      refused_.load(std::memory_order_relaxed) + write_failed_.load(std::memory_order_relaxed);
  s.transport.overflowed = overflowed_.load(std::memory_order_relaxed);
  return s;
}

void DdsTransport::dispatch(msg::Topic topic, const void* sample, TimePoint now) {
  const RobotId key = msg::message_key(topic, sample);
  for (const Subscription& sub : subscriptions_) {
    if (sub.topic != topic || (sub.key != kAnyRobot && sub.key != key)) continue;
    sub.sink->on_sample(topic, sample, now);
    ++stats_.transport.delivered;
  }
}

template <class Msg>
void DdsTransport::drain(msg::Topic topic, TimePoint now) {
  using Idl = typename IdlSample<Msg>::Type;
  const dds_entity_t reader = readers_[index(topic)];
  for (;;) {
    void* buf[kTakeBatch] = {};
    dds_sample_info_t info[kTakeBatch];
    const dds_return_t n = dds_take(reader, buf, info, kTakeBatch, kTakeBatch);
    if (n <= 0) break;
    for (dds_return_t k = 0; k < n; ++k) {
      if (!info[k].valid_data) continue;  // instance disposed / unregistered
      Msg m;
      if (!from_idl(*static_cast<const Idl*>(buf[k]), m)) {
        ++stats_.malformed;
        continue;
      }
      dispatch(topic, &m, now);
    }
    dds_return_loan(reader, buf, n);
    if (static_cast<std::uint32_t>(n) < kTakeBatch) break;
  }
  dds_sample_lost_status_t lost{};
  if (dds_get_sample_lost_status(reader, &lost) == DDS_RETCODE_OK) {
    stats_.transport.dropped += lost.total_count_change;
  }
  dds_requested_deadline_missed_status_t missed{};
  if (dds_get_requested_deadline_missed_status(reader, &missed) == DDS_RETCODE_OK) {
    stats_.deadline_missed += missed.total_count_change;
  }
}

void DdsTransport::poll(TimePoint now) {
  for (const msg::TopicInfo& info : msg::kTopicTable) {
    if (readers_[index(info.topic)] <= 0) continue;
    msg::visit_message_type(info.topic, [&]<class Msg>() { drain<Msg>(info.topic, now); });
  }
}

}  // namespace colag::platform::dds
