#pragma once
// The ROS 2 message types the fleet's telemetry uses, by their DDS type name: the generated
// descriptor (to read and serialise samples) and the ROS 2 name (MCAP's schema name). For tools
// that meet the types on the wire (colag_record).
#include <dds/dds.h>

#include <string_view>

namespace colag::hal::ros2 {

struct Ros2Type {
  std::string_view dds_name;  // "nav_msgs::msg::dds_::Odometry_"
  std::string_view ros_name;  // "nav_msgs/msg/Odometry"
  const dds_topic_descriptor_t* descriptor;
};

// The type of `dds_name`; null when it is not one of the telemetry's.
const Ros2Type* find_ros2_type(std::string_view dds_name);

}  // namespace colag::hal::ros2
