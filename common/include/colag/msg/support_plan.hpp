#pragma once
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::msg {

struct SupportStop {
  RobotId ugv_id = 0;
  double point_m[3] = {};   // support point at flight altitude
  double eta_s = 0.0;       // planned arrival, from the plan's stamp
  double deadline_s = 0.0;  // the UGV's predicted collision time, from the plan's stamp
  friend bool operator==(const SupportStop&, const SupportStop&) = default;
};

// The UAV's current visiting order (UAV -> everyone, on every change).
struct SupportPlan {
  TimePoint stamp;
  RobotId uav_id = 0;
  std::uint32_t seq = 0;
  std::uint16_t stop_count = 0;
  double total_lateness_s = 0.0;  // sum over stops of max(0, eta - deadline)
  SupportStop stops[limits::kMaxSupportRequests] = {};
  friend bool operator==(const SupportPlan&, const SupportPlan&) = default;
};

}  // namespace colag::msg
