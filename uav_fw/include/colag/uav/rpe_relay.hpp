#pragma once
// The camera's detections become RelativePose messages for the UGVs, stamped with the
// detection time (the UAV publishes every odometry sample too, so each UGV can find the UAV's
// pose at that instant). Malformed detections are refused.
#include "colag/common/status.hpp"
#include "colag/hal/relative_pose_sensor.hpp"
#include "colag/msg/relative_pose.hpp"

namespace colag::uav {

Result<msg::RelativePose> to_message(const hal::RelativePoseDetection& d, RobotId uav_id);

}  // namespace colag::uav
