#pragma once
// What every robot's ROS 2 telemetry opens first: its participant on the fleet's domain (with
// `participant_qos`: the robot's DDS Security, or null), and the writers of <ns>/odom (sensor
// data QoS) and /tf (tf2's).
#include <cstdint>
#include <string>
#include <string_view>

#include "colag/hal/dds/device_participant.hpp"

namespace colag::hal::ros2 {

struct PoseWriters {
  dds_entity_t odom = 0, tf = 0;
  // False with `error` ("ROS 2 telemetry: ...") when DDS refuses.
  bool open(dds::DeviceParticipant& dds, std::uint32_t domain, const dds_qos_t* participant_qos,
            std::string_view ns, std::string& error);
};

}  // namespace colag::hal::ros2
