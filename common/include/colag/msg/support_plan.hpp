#pragma once
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/sequence.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

struct SupportStop {
  RobotId ugv_id = 0;
  double point_m[3] = {};   // support point at flight altitude
  double eta_s = 0.0;       // planned arrival, from the plan's stamp
  double deadline_s = 0.0;  // the UGV's predicted collision time, from the plan's stamp
  friend bool operator==(const SupportStop&, const SupportStop&) = default;
};
COLAG_MESSAGE_FIELDS(SupportStop, ugv_id, point_m, eta_s, deadline_s);

// The UAV's current visiting order (UAV -> everyone, on every change).
struct SupportPlan {
  TimePoint stamp;
  RobotId uav_id = 0;
  std::uint32_t seq = 0;
  double total_lateness_s = 0.0;  // sum over stops of max(0, eta - deadline)
  Sequence<SupportStop, limits::kMaxSupportRequests> stops;
  friend bool operator==(const SupportPlan&, const SupportPlan&) = default;
};
COLAG_MESSAGE_FIELDS(SupportPlan, stamp, uav_id, seq, total_lateness_s, stops);

// Reliable; only the latest plan matters.
template <>
inline constexpr TopicSpec<SupportPlan> kTopicSpec<SupportPlan> = {
    "colag_support_plan", &SupportPlan::uav_id, Reliability::kReliable, 1, Duration::zero()};

}  // namespace colag::msg
