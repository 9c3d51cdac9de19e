#include "colag/hal/ros2/pose_writers.hpp"

#include "colag/hal/ros2/ros2_names.hpp"
#include "ros2_msgs.h"

namespace colag::hal::ros2 {

bool PoseWriters::open(dds::DeviceParticipant& dds, std::uint32_t domain,
                       const dds_qos_t* participant_qos, std::string_view ns, std::string& error) {
  if (dds.init(domain, participant_qos)) {
    odom = dds.writer(ros2_dds_topic(ns, "odom"), nav_msgs_msg_dds__Odometry__desc,
                      dds::kSensorDataQos);
    tf = dds.writer(ros2_dds_topic("/tf"), tf2_msgs_msg_dds__TFMessage__desc, dds::kTfQos);
  }
  if (odom > 0 && tf > 0) return true;
  error = "ROS 2 telemetry: " + dds.last_error();
  return false;
}

}  // namespace colag::hal::ros2
