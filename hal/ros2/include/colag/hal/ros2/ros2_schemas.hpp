#pragma once
// The ROS 2 message definitions (.msg text) of the types the fleet's telemetry uses, as MCAP's
// `ros2` profile stores them (schema encoding `ros2msg`): the type's own text, then each type it
// uses, once, after a line of 80 '=' and a `MSG: pkg/Type` line. Facts from the ROS 2 Jazzy
// interfaces (common_interfaces, rcl_interfaces); comments and default values dropped.
#include <string>
#include <string_view>

namespace colag::hal::ros2 {

// The schema of `type` ("nav_msgs/msg/Odometry"); empty for a type not known here.
std::string ros2msg_schema(std::string_view type);

}  // namespace colag::hal::ros2
