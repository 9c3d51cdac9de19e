#pragma once
// The DDS participant of a device driver that talks to software we did not write (PX4's agent,
// FAST-LIO, the Livox driver, ROS 2 tools): its topics carry their ROS 2 names and types, best
// effort as those publishers send (a reliable reader would not match them), and no XTypes type
// information: peers match them by type name alone, as ROS 2's own middlewares do (a type
// object that differs in some detail would otherwise keep a matching peer apart). One per
// driver; deleting it deletes everything under it.
#include <dds/dds.h>

#include <memory>
#include <string>
#include <vector>

#include "colag/common/status.hpp"

namespace colag::hal::dds {

class DeviceParticipant {
 public:
  DeviceParticipant() = default;
  ~DeviceParticipant() {
    if (participant_ > 0) dds_delete(participant_);
  }
  DeviceParticipant(const DeviceParticipant&) = delete;
  DeviceParticipant& operator=(const DeviceParticipant&) = delete;

  // `qos`: the participant's (e.g. DDS Security's properties); null: Cyclone's defaults.
  Status init(std::uint32_t domain, const dds_qos_t* qos = nullptr) {
    participant_ = dds_create_participant(domain, qos, nullptr);
    return participant_ > 0 ? Status::ok() : fail(participant_, "participant");
  }
  // A best-effort, volatile endpoint on `topic` (keep-last `depth`); 0 with last_error() set.
  // `wire_type`: the type name on the wire, when it is not the one `type` was declared with.
  dds_entity_t writer(const std::string& topic, const dds_topic_descriptor_t& type,
                      const char* wire_type = nullptr) {
    return endpoint(topic, type, wire_type, true, {.depth = 1});
  }
  dds_entity_t reader(const std::string& topic, const dds_topic_descriptor_t& type, int depth,
                      const char* wire_type = nullptr) {
    return endpoint(topic, type, wire_type, false, {.depth = depth});
  }
  // An endpoint with ROS 2's QoS for its kind: sensor data best effort; the default (status,
  // paths, /tf) reliable; maps reliable and transient-local (a late joiner gets the last one).
  struct Qos {
    bool reliable = false;
    bool transient_local = false;
    int depth = 1;
  };
  dds_entity_t writer(const std::string& topic, const dds_topic_descriptor_t& type, Qos qos) {
    return endpoint(topic, type, nullptr, true, qos);
  }
  dds_entity_t reader(const std::string& topic, const dds_topic_descriptor_t& type, Qos qos) {
    return endpoint(topic, type, nullptr, false, qos);
  }
  dds_entity_t participant() const { return participant_; }
  // What failed last: "topic NAME: reason".
  const std::string& last_error() const { return error_; }

 private:
  Status fail(dds_return_t rc, const std::string& what) {
    error_ = what + ": " + dds_strretcode(rc);
    return {Errc::kUnavailable, "DDS entity not created"};
  }
  dds_entity_t endpoint(const std::string& name, const dds_topic_descriptor_t& type,
                        const char* wire_type, bool write, Qos q) {
    const dds_topic_descriptor_t& d = *types_.emplace_back(std::make_unique<dds_topic_descriptor_t>(
        by_name(type, wire_type ? wire_type : type.m_typename)));
    const dds_entity_t topic = dds_create_topic(participant_, &d, name.c_str(), nullptr, nullptr);
    if (topic < 0) {
      (void)fail(topic, "topic " + name);
      return 0;
    }
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, q.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                         DDS_MSECS(100));
    dds_qset_durability(
        qos, q.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, q.depth);
    const dds_entity_t e = write ? dds_create_writer(participant_, topic, qos, nullptr)
                                 : dds_create_reader(participant_, topic, qos, nullptr);
    dds_delete_qos(qos);
    if (e < 0) {
      (void)fail(e, (write ? "writer " : "reader ") + name);
      return 0;
    }
    return e;
  }

  // `d` named `name` on the wire, without type information.
  static dds_topic_descriptor_t by_name(const dds_topic_descriptor_t& d, const char* name) {
    return {d.m_size,     d.m_align,    d.m_flagset & ~DDS_TOPIC_XTYPES_METADATA,
            d.m_nkeys,    name,         d.m_keys,
            d.m_nops,     d.m_ops,      d.m_meta,
            {nullptr, 0}, {nullptr, 0}, d.restrict_data_representation};
  }

  dds_entity_t participant_ = 0;
  std::vector<std::unique_ptr<dds_topic_descriptor_t>> types_;  // outlive their topics
  std::string error_;
};

// ROS 2's QoS presets, as its tools expect them.
inline constexpr DeviceParticipant::Qos kSensorDataQos{};  // best effort, keep last 1
inline constexpr DeviceParticipant::Qos kDefaultQos{.reliable = true, .depth = 10};
inline constexpr DeviceParticipant::Qos kLatchedQos{
    .reliable = true, .transient_local = true, .depth = 1};  // maps: a late joiner's too
inline constexpr DeviceParticipant::Qos kTfQos{.reliable = true, .depth = 100};  // tf2's

}  // namespace colag::hal::dds
