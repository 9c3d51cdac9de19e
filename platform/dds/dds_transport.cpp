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
bool per_ugv(msg::Topic t) {
  return msg::topic_info(t).delivery == msg::Delivery::kPerUgv;
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
  return qos;
}

void DdsTransport::partition_name(RobotId ugv, char* out, std::size_t size) const {
  const char* base = config_.partition != nullptr ? config_.partition : "";
  if (ugv == kAnyRobot) {
    std::snprintf(out, size, "%s", base);
  } else {
    std::snprintf(out, size, "%s%sugv%u", base, base[0] != '\0' ? "." : "",
                  static_cast<unsigned>(ugv));
  }
}

dds_entity_t DdsTransport::group(RobotId ugv, Groups& groups, CreateGroup create) {
  dds_entity_t& g = ugv == kAnyRobot ? groups.fleet : groups.ugv[ugv];
  if (g > 0) return g;
  char name[128];
  partition_name(ugv, name, sizeof name);
  dds_qos_t* qos = dds_create_qos();
  dds_qset_partition1(qos, name);
  g = create(participant_, qos, nullptr);
  dds_delete_qos(qos);
  return g;
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

  if (config_.ugvs.count == 0 || config_.ugvs.first + config_.ugvs.count > limits::kMaxUgvs)
    return {Errc::kInvalidArgument, "DDS transport: UGV range outside 0 .. kMaxUgvs-1"};
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
    // A writer in each partition it may write to: the fleet's, or each of its UGVs'.
    const bool each_ugv = per_ugv(info.topic);
    const RobotId first = each_ugv ? config_.ugvs.first : kAnyRobot;
    const int writers = config.publishes[i] ? (each_ugv ? config_.ugvs.count : 1) : 0;
    for (int k = 0; k < writers; ++k) {
      const RobotId ugv = each_ugv ? static_cast<RobotId>(first + k) : kAnyRobot;
      const dds_entity_t pub = group(ugv, publishers_, dds_create_publisher);
      dds_entity_t& w = writers_[i][each_ugv ? ugv : 0];
      w = pub > 0 ? dds_create_writer(pub, topics_[i], qos, nullptr) : pub;
      if (w < 0) {
        dds_delete_qos(qos);
        return fail(w, "dds_create_writer failed");
      }
    }
    dds_delete_qos(qos);
  }
  writer_ = std::thread([this] { writer_loop(); });
  return Status::ok();
}

Status DdsTransport::add_reader(msg::Topic topic, RobotId ugv) {
  for (const Reader& r : readers_)
    if (r.topic == topic && r.ugv == ugv) return Status::ok();
  const dds_entity_t sub = group(ugv, subscribers_, dds_create_subscriber);
  if (sub < 0) return fail(sub, "dds_create_subscriber failed");
  dds_qos_t* qos = make_qos(msg::topic_info(topic));
  const dds_entity_t reader = dds_create_reader(sub, topics_[index(topic)], qos, nullptr);
  dds_delete_qos(qos);
  if (reader < 0) return fail(reader, "dds_create_reader failed");
  if (!readers_.push_back({reader, topic, ugv})) {
    (void)dds_delete(reader);
    return {Errc::kCapacityExceeded, "DDS transport: too many readers"};
  }
  return Status::ok();
}

Status DdsTransport::subscribe(msg::Topic topic, RobotId key, SampleSink& sink) {
  if (participant_ <= 0) return {Errc::kNotReady, "DDS transport not initialised"};
  if (index(topic) >= msg::kTopicCount) return {Errc::kInvalidArgument, "unknown topic"};
  if (!per_ugv(topic)) {
    if (Status s = add_reader(topic, kAnyRobot); !s) return s;
  } else if (key != kAnyRobot) {
    if (!config_.ugvs.contains(key))
      return {Errc::kInvalidArgument, "DDS transport: that UGV's partition is not this robot's"};
    if (Status s = add_reader(topic, key); !s) return s;
  } else {
    for (std::uint16_t k = 0; k < config_.ugvs.count; ++k) {
      if (Status s = add_reader(topic, static_cast<RobotId>(config_.ugvs.first + k)); !s) return s;
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
  dds_entity_t writer = 0;
  if (i < msg::kTopicCount && sample != nullptr) {
    const RobotId key = per_ugv(topic) ? msg::message_key(topic, sample) : RobotId{0};
    writer = key < limits::kMaxUgvs ? writers_[i][key] : 0;
  }
  if (writer <= 0) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    return {Errc::kInvalidArgument, "DDS transport: no writer for this topic (or this UGV)"};
  }
  {
    const std::lock_guard<std::mutex> lock(out_mutex_);
    if (out_size_ == outbox_.size()) {
      overflowed_.fetch_add(1, std::memory_order_relaxed);
      return {Errc::kCapacityExceeded, "DDS transport: outbox full (the writer is behind)"};
    }
    Outgoing& slot = outbox_[(out_head_ + out_size_) % outbox_.size()];
    slot.topic = topic;
    slot.writer = writer;
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
    const Status s = msg::visit_message_type(
        out.topic, [&]<class Msg>() { return write<Msg>(out.writer, out.bytes.data()); });
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
void DdsTransport::drain(const Reader& r, TimePoint now) {
  using Idl = typename IdlSample<Msg>::Type;
  const dds_entity_t reader = r.reader;
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
      if (r.ugv != kAnyRobot && msg::MessageTraits<Msg>::key(m) != r.ugv) {
        ++stats_.misaddressed;
        continue;
      }
      dispatch(r.topic, &m, now);
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
  for (const Reader& r : readers_)
    msg::visit_message_type(r.topic, [&]<class Msg>() { drain<Msg>(r, now); });
}

}  // namespace colag::platform::dds
