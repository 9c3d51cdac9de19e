#pragma once
// Transport over Cyclone DDS (C API): one participant per robot, one DDS topic per message of
// msg::Messages with its topic's QoS (msg::kTopicTable), keyed by robot id. Samples are taken on
// the caller's thread in poll(), converted back to message structs and handed to the sinks, so
// tasks never see a DDS thread. Our code allocates nothing after init; Cyclone allocates internally
// when serialising (that is the library's own memory, bounded by the QoS history depths).
#include <dds/dds.h>

#include <array>
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/platform/dds_security_config.hpp"
#include "colag/platform/transport.hpp"

namespace colag::platform::dds {

struct DdsConfig {
  std::uint32_t domain_id = 0;
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
  Status publish(msg::Topic topic, const void* sample) override;
  void poll(TimePoint now) override;
  TransportStats stats() const override { return stats_.transport; }
  const DdsStats& dds_stats() const { return stats_; }
  // The raw return code of the last failed DDS call (see dds_strretcode), for diagnostics.
  dds_return_t last_error() const { return last_error_; }

 private:
  struct Subscription {
    msg::Topic topic;
    RobotId key;
    SampleSink* sink;
  };
  template <class Msg>
  Status write(dds_entity_t writer, const void* sample);
  template <class Msg>
  void drain(msg::Topic topic, TimePoint now);
  void dispatch(msg::Topic topic, const void* sample, TimePoint now);
  dds_qos_t* make_qos(const msg::TopicInfo& info) const;
  Status fail(dds_return_t rc, const char* what);
  Status security_qos(dds_qos_t* qos) const;

  DdsConfig config_;
  dds_entity_t participant_ = 0;
  std::array<dds_entity_t, msg::kTopicCount> topics_{};
  std::array<dds_entity_t, msg::kTopicCount> writers_{};
  std::array<dds_entity_t, msg::kTopicCount> readers_{};
  StaticVector<Subscription, limits::kMaxSubscriptions> subscriptions_;
  DdsStats stats_;
  dds_return_t last_error_ = 0;
};

}  // namespace colag::platform::dds
