#pragma once
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

// Fleet time is the clock of one UAV, the time server (UAV 0 unless configured). Every other
// robot measures its own clock against it with NTP-style exchanges (ClockOffsetFilter): it asks
// with its own time, the server answers at once with its receive and send times. Every stamp on
// the other topics is fleet time; each robot converts at its edges (platform::FleetClock). The
// UGVs ask on the first pair of topics (in their own partitions), the other UAVs on the second.

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

// UAV -> the time server: "what time is it?" (another UAV: its stamps must be fleet time too).
struct UavClockRequest {
  TimePoint stamp;  // t1: sent, the asking UAV's own clock
  RobotId uav_id = 0;
  std::uint32_t seq = 0;
  friend bool operator==(const UavClockRequest&, const UavClockRequest&) = default;
};
COLAG_MESSAGE_FIELDS(UavClockRequest, stamp, uav_id, seq);
template <>
inline constexpr TopicSpec<UavClockRequest> kTopicSpec<UavClockRequest> = {
    "colag_uav_clock_request", &UavClockRequest::uav_id, Reliability::kBestEffort, 1,
    Duration::zero(),          Delivery::kFleet};

// The time server -> the UAV that asked.
struct UavClockReply {
  TimePoint stamp;  // t3: sent, the server's clock
  RobotId server_id = 0;
  RobotId uav_id = 0;  // who asked
  std::uint32_t seq = 0;
  TimePoint request_stamp;  // t1, echoed
  TimePoint received;       // t2: the request received, the server's clock
  friend bool operator==(const UavClockReply&, const UavClockReply&) = default;
};
COLAG_MESSAGE_FIELDS(UavClockReply, stamp, server_id, uav_id, seq, request_stamp, received);
template <>
inline constexpr TopicSpec<UavClockReply> kTopicSpec<UavClockReply> = {
    "colag_uav_clock_reply", &UavClockReply::uav_id, Reliability::kBestEffort, 1,
    Duration::zero(),        Delivery::kFleet};

}  // namespace colag::msg
