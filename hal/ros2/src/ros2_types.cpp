#include "colag/hal/ros2/ros2_types.hpp"

#include <array>

#include "ros2_msgs.h"

namespace colag::hal::ros2 {

namespace {

const std::array kTypes = {
    Ros2Type{"nav_msgs::msg::dds_::Odometry_", "nav_msgs/msg/Odometry",
             &nav_msgs_msg_dds__Odometry__desc},
    Ros2Type{"nav_msgs::msg::dds_::Path_", "nav_msgs/msg/Path", &nav_msgs_msg_dds__Path__desc},
    Ros2Type{"nav_msgs::msg::dds_::OccupancyGrid_", "nav_msgs/msg/OccupancyGrid",
             &nav_msgs_msg_dds__OccupancyGrid__desc},
    Ros2Type{"tf2_msgs::msg::dds_::TFMessage_", "tf2_msgs/msg/TFMessage",
             &tf2_msgs_msg_dds__TFMessage__desc},
    Ros2Type{"geometry_msgs::msg::dds_::PoseStamped_", "geometry_msgs/msg/PoseStamped",
             &geometry_msgs_msg_dds__PoseStamped__desc},
    Ros2Type{"visualization_msgs::msg::dds_::MarkerArray_", "visualization_msgs/msg/MarkerArray",
             &visualization_msgs_msg_dds__MarkerArray__desc},
    Ros2Type{"colag_msgs::msg::dds_::UgvStatus_", "colag_msgs/msg/UgvStatus",
             &colag_msgs_msg_dds__UgvStatus__desc},
    Ros2Type{"colag_msgs::msg::dds_::UavStatus_", "colag_msgs/msg/UavStatus",
             &colag_msgs_msg_dds__UavStatus__desc},
    Ros2Type{"colag_msgs::msg::dds_::UgvCommand_", "colag_msgs/msg/UgvCommand",
             &colag_msgs_msg_dds__UgvCommand__desc},
};

}  // namespace

const Ros2Type* find_ros2_type(std::string_view dds_name) {
  for (const Ros2Type& t : kTypes)
    if (t.dds_name == dds_name) return &t;
  return nullptr;
}

}  // namespace colag::hal::ros2
