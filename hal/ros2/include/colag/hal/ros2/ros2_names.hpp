#pragma once
// ROS 2 names on the wire: the topic `/ns/a/b` is the DDS topic `rt/ns/a/b`. One place for the
// PX4 driver, the ROS 2 drivers and colag_world's flight stack.
#include <string>
#include <string_view>

namespace colag::hal::ros2 {

// The DDS topic of ROS topic `name` in namespace `ns` (either may start or end with '/'; an
// empty namespace is none): ("", "/Odometry") -> "rt/Odometry", ("/uav1/", "fmu/in/x") ->
// "rt/uav1/fmu/in/x".
std::string ros2_dds_topic(std::string_view ns, std::string_view name);
inline std::string ros2_dds_topic(std::string_view name) {
  return ros2_dds_topic({}, name);
}

}  // namespace colag::hal::ros2
