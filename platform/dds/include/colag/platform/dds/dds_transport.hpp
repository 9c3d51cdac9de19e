#pragma once
// Transport over Cyclone DDS (C API): one participant per robot, one DDS topic per message of
// msg::Messages with its topic's QoS (msg::kTopicTable), keyed by robot id. A kPerUgv topic's
// samples travel in the partition of the UGV their key names ("ugv<id>", after the configured
// partition if any: "<partition>.ugv<id>"): a writer and a reader per UGV partition, so that a
// UGV's participant receives only its own, and DDS Security can bind UGV i to ugv<i>. A reader
// takes only samples whose key is its partition's UGV (others are counted as misaddressed:
// a certificate cannot speak for another UGV). kFleet topics use the configured partition.
// Samples are taken on
// the caller's thread in poll(), converted back to message structs and handed to the sinks, so
// tasks never see a DDS thread. publish() copies the sample into a fixed outbox and returns: the
// transport's writer thread hands it to Cyclone, which allocates for every write (a serialised
// sample and its buffer), so that no task thread calls malloc. Nothing of ours allocates after
// init.
#include <dds/dds.h>

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <semaphore>
#include <thread>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/platform/dds_security_config.hpp"
#include "colag/platform/transport.hpp"

namespace colag::platform::dds {

// The UGVs whose partitions a participant joins: UGV i only its own ({i, 1}); the UAV and
// listeners every UGV of the fleet.
struct UgvRange {
  RobotId first = 0;
  std::uint16_t count = limits::kMaxUgvs;
  bool contains(RobotId id) const { return id >= first && id - first < count; }
};

struct DdsConfig {
  std::uint32_t domain_id = 0;
  UgvRange ugvs;
  // DDS partition of every reader and writer; "" = the default partition. Lets a simulator's
  // topics and a robot's own live side by side without mixing.
  const char* partition = "";
  // Topics this participant may write (a writer is created at init for each): a UGV need not
  // announce writers for map patches, and DDS Security permissions can forbid them.
  std::array<bool, msg::kTopicCount> publishes = [] {
    std::array<bool, msg::kTopicCount> all{};
    all.fill(true);
    return all;
  }();
  // Writers for these messages' topics only.
  template <class... Msg>
  void publish_only() {
    publishes = {};
    ((publishes[static_cast<std::size_t>(msg::topic_of<Msg>)] = true), ...);
  }
  // DDS Security (authentication, access control, encryption); off when empty.
  DdsSecurityConfig security;
};

struct DdsStats {
  TransportStats transport;
  std::uint64_t malformed = 0;        // samples that could not be converted to a message
  std::uint64_t misaddressed = 0;     // a per-UGV sample in another UGV's partition: dropped
  std::uint64_t deadline_missed = 0;  // a key went silent longer than its topic's deadline
};

class DdsTransport final : public Transport {
 public:
  DdsTransport() = default;
  ~DdsTransport() override;  // deletes the participant and every entity under it
  DdsTransport(const DdsTransport&) = delete;
  DdsTransport& operator=(const DdsTransport&) = delete;

  Status init(const DdsConfig& config);

  Status subscribe(msg::Topic topic, RobotId key, SampleSink& sink) override;
  using Transport::publish;  // the typed overload
  // Queues the sample for the writer thread; refused when the outbox is full (counted as
  // overflowed) or the topic has no writer (for a per-UGV topic: in that UGV's partition).
  Status publish(msg::Topic topic, const void* sample) override;
  void poll(TimePoint now) override;
  TransportStats stats() const override { return dds_stats().transport; }
  DdsStats dds_stats() const;
  // Waits until every sample published so far has been handed to DDS.
  void flush();
  // The raw return code of the last failed DDS call (see dds_strretcode), for diagnostics.
  dds_return_t last_error() const { return last_error_; }

 private:
  struct Subscription {
    msg::Topic topic;
    RobotId key;
    SampleSink* sink;
  };
  struct Reader {
    dds_entity_t reader;
    msg::Topic topic;
    RobotId ugv;  // a per-UGV topic's partition; kAnyRobot: a fleet topic
  };
  struct Outgoing {
    msg::Topic topic{};
    dds_entity_t writer = 0;
    alignas(std::max_align_t) std::array<std::byte, msg::kMaxMessageBytes> bytes{};
  };
  // Writers of a topic: [0] for a fleet topic, [ugv id] for a per-UGV topic.
  using Writers = std::array<dds_entity_t, limits::kMaxUgvs>;
  template <class Msg>
  Status write(dds_entity_t writer, const void* sample);
  void writer_loop();
  template <class Msg>
  void drain(const Reader& r, TimePoint now);
  void dispatch(msg::Topic topic, const void* sample, TimePoint now);
  dds_qos_t* make_qos(const msg::TopicInfo& info) const;
  Status fail(dds_return_t rc, const char* what);
  // Publishers (or subscribers), one per partition: the fleet's and each UGV's.
  struct Groups {
    dds_entity_t fleet = 0;
    std::array<dds_entity_t, limits::kMaxUgvs> ugv{};
  };
  using CreateGroup = dds_entity_t (*)(dds_entity_t, const dds_qos_t*, const dds_listener_t*);
  // The publisher / subscriber of a partition (kAnyRobot: the fleet's), created on first use.
  dds_entity_t group(RobotId ugv, Groups& groups, CreateGroup create);
  void partition_name(RobotId ugv, char* out, std::size_t size) const;
  Status add_reader(msg::Topic topic, RobotId ugv);

  DdsConfig config_;
  dds_entity_t participant_ = 0;
  std::array<dds_entity_t, msg::kTopicCount> topics_{};
  std::array<Writers, msg::kTopicCount> writers_{};
  Groups publishers_, subscribers_;
  StaticVector<Reader, limits::kMaxDdsReaders> readers_;
  StaticVector<Subscription, limits::kMaxSubscriptions> subscriptions_;
  DdsStats stats_;  // what poll() counts (the executor's thread)
  dds_return_t last_error_ = 0;

  // The outbox: publish() fills a slot under the mutex (a copy, nothing allocated); the writer
  // thread copies it out in order and writes it outside the mutex.
  std::array<Outgoing, limits::kDdsOutboxDepth> outbox_{};
  std::size_t out_head_ = 0, out_size_ = 0;  // guarded by out_mutex_
  mutable std::mutex out_mutex_;
  std::counting_semaphore<limits::kDdsOutboxDepth + 1> out_pending_{0};
  std::atomic<std::uint64_t> queued_{0}, handled_{0};  // publish()ed, and finished by the writer
  std::atomic<std::uint64_t> written_{0}, write_failed_{0}, overflowed_{0}, refused_{0};
  std::atomic<bool> stopping_{false};
  std::thread writer_;
};

}  // namespace colag::platform::dds
