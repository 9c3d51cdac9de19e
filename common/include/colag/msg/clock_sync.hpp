#pragma once
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

// Fleet time is the UAV's clock. Each UGV measures its own clock against it with NTP-style
// exchanges (ClockOffsetFilter): it asks with its own time, the UAV answers at once with its
// receive and send times. Every stamp on the other topics is fleet time; a UGV converts at its
// edges (ugv::FleetClock).

// UGV -> UAV: "what time is it?"
struct ClockRequest {
  TimePoint stamp;  // t1: sent, the UGV's own clock
  RobotId ugv_id = 0;
  std::uint32_t seq = 0;
  friend bool operator==(const ClockRequest&, const ClockRequest&) = default;
};
COLAG_MESSAGE_FIELDS(ClockRequest, stamp, ugv_id, seq);
// Lost requests are simply asked again: best effort, only the newest per UGV.
template <>
inline constexpr TopicSpec<ClockRequest> kTopicSpec<ClockRequest> = {
    "colag_clock_request", &ClockRequest::ugv_id, Reliability::kBestEffort, 1,
    Duration::zero(),      Delivery::kPerUgv};

// UAV -> the UGV that asked.
struct ClockReply {
  TimePoint stamp;  // t3: sent, the UAV's clock
  RobotId uav_id = 0;
  RobotId ugv_id = 0;       // who asked
  std::uint32_t seq = 0;    // the request's
  TimePoint request_stamp;  // t1, echoed: the reply carries the whole exchange
  TimePoint received;       // t2: the request received, the UAV's clock
  friend bool operator==(const ClockReply&, const ClockReply&) = default;
};
COLAG_MESSAGE_FIELDS(ClockReply, stamp, uav_id, ugv_id, seq, request_stamp, received);
template <>
inline constexpr TopicSpec<ClockReply> kTopicSpec<ClockReply> = {
    "colag_clock_reply", &ClockReply::ugv_id, Reliability::kBestEffort, 1,
    Duration::zero(),    Delivery::kPerUgv};

}  // namespace colag::msg
