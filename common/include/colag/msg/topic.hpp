#pragma once
// A message's topic, declared beside the message: its DDS name, the field it is keyed by (the
// robot it is from or for), and its quality of service.
#include <cstdint>

#include "colag/common/time.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::msg {

enum class Reliability : std::uint8_t { kBestEffort, kReliable };

template <class Msg>
struct TopicSpec {
  const char* name;   // DDS topic name
  RobotId Msg::*key;  // samples are filed (and filtered) by this robot id
  Reliability reliability;
  std::uint16_t history_depth;  // keep-last depth per key (robot)
  Duration deadline;            // expected max gap between samples of one key; 0 = none
};

// Specialised for each message, in its header.
template <class Msg>
inline constexpr TopicSpec<Msg> kTopicSpec = [] {
  static_assert(sizeof(Msg) == 0, "declare the message's topic: kTopicSpec<Msg> in its header");
  return TopicSpec<Msg>{};
}();

}  // namespace colag::msg
