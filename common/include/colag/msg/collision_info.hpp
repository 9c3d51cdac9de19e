#pragma once
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

// A UGV's request for support (UGV -> UAV), or the cancellation of its earlier request.
// Latest value per UGV wins: the transport keeps it reliably, so a cancel is never lost.
struct CollisionInfo {
  TimePoint stamp;
  RobotId ugv_id = 0;
  std::uint32_t seq = 0;
  bool cancel = false;               // true: no support needed any more; fields below unused
  double collision_point_m[2] = {};  // p_pc: centre of the first 3-sigma ellipse that touches
  double support_point_m[2] = {};    // p_ps: where the UAV should go
  double time_to_collision_s = 0.0;  // t_pc, counted from `stamp`
  friend bool operator==(const CollisionInfo&, const CollisionInfo&) = default;
};
COLAG_MESSAGE_FIELDS(CollisionInfo, stamp, ugv_id, seq, cancel, collision_point_m, support_point_m,
                     time_to_collision_s);

// Reliable, and only the latest per UGV is kept, so a cancel always supersedes its request.
template <>
inline constexpr TopicSpec<CollisionInfo> kTopicSpec<CollisionInfo> = {
    "colag_collision_info", &CollisionInfo::ugv_id, Reliability::kReliable, 1,
    Duration::zero(),       Delivery::kPerUgv};

}  // namespace colag::msg
