#pragma once
// A message's topic, declared beside the message: its DDS name, the field it is keyed by (the
// robot it is from or for), and its quality of service.
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::msg {

enum class Reliability : std::uint8_t { kBestEffort, kReliable };

// Who receives a topic's samples. kFleet: every robot that reads the topic (the UAV's odometry
// and plan). kPerUgv: only the UGV the sample's key names, and the UAV; on DDS each UGV's such
// samples travel in that UGV's own partition ("ugv<id>"), so a UGV receives neither the patches,
// poses and clock replies meant for the others nor their statuses, and its bytes in do not grow
// with the fleet; DDS Security permissions then bind UGV i to partition ugv<i>.
enum class Delivery : std::uint8_t { kFleet, kPerUgv };

template <class Msg>
struct TopicSpec {
  const char* name;   // DDS topic name
  RobotId Msg::*key;  // samples are filed (and filtered) by this robot id
  Reliability reliability;
  std::uint16_t history_depth;  // keep-last depth per key (robot)
  Duration deadline;            // expected max gap between samples of one key; 0 = none
  Delivery delivery = Delivery::kFleet;
};

// Specialised for each message, in its header.
template <class Msg>
inline constexpr TopicSpec<Msg> kTopicSpec = [] {
  static_assert(sizeof(Msg) == 0, "declare the message's topic: kTopicSpec<Msg> in its header");
  return TopicSpec<Msg>{};
}();

}  // namespace colag::msg
