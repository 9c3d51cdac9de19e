#pragma once
// DDS Security on a participant: the DDS Security spec's dds.sec.* properties for Cyclone's
// authentication, access-control and cryptography plugins, from the six files
// scripts/security/make-pki writes for a robot. Every participant of a secured robot takes them
// (the mission transport, the ROS 2 telemetry).
#include <dds/dds.h>

#include "colag/common/status.hpp"
#include "colag/platform/dds_security_config.hpp"

namespace colag::platform::dds {

// Adds the properties to `qos`. Every file must be readable: a typo fails here with its name,
// not later as an opaque DDS error.
Status add_security(const DdsSecurityConfig& sec, dds_qos_t* qos);

// A robot participant's QoS: DDS Security's properties when `sec` is on, else none (null).
class ParticipantQos {
 public:
  ParticipantQos() = default;
  ~ParticipantQos() {
    if (qos_ != nullptr) dds_delete_qos(qos_);
  }
  ParticipantQos(const ParticipantQos&) = delete;
  ParticipantQos& operator=(const ParticipantQos&) = delete;
  Status init(const DdsSecurityConfig& sec) {
    if (!sec.enabled()) return Status::ok();
    qos_ = dds_create_qos();
    return add_security(sec, qos_);
  }
  const dds_qos_t* get() const { return qos_; }

 private:
  dds_qos_t* qos_ = nullptr;
};

}  // namespace colag::platform::dds
