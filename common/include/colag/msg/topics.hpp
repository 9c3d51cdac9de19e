#pragma once
// The robot-to-robot topics: one per message in `Messages`. A message declares itself in its
// own header (the struct, its field list, its topic: name, key, QoS); everything else is derived
// from that: the topic table every transport uses, the DDS IDL and conversions (generated), the
// round-trip and fuzz tests. Adding a topic is one declaration and one line in Messages.
#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>

#include "colag/common/time.hpp"
#include "colag/msg/clock_sync.hpp"
#include "colag/msg/collision_info.hpp"
#include "colag/msg/map_patch.hpp"
#include "colag/msg/nearby_ugvs.hpp"
#include "colag/msg/relative_pose.hpp"
#include "colag/msg/support_plan.hpp"
#include "colag/msg/uav_odometry.hpp"
#include "colag/msg/ugv_status.hpp"
#include "colag/msg/wire_size.hpp"

namespace colag::msg {

// Every message that crosses between robots, in topic order.
using Messages =
    std::tuple<UavOdometry, RelativePose, MapPatch, CollisionInfo, UgvStatus, SupportPlan,
               ClockRequest, ClockReply, NearbyUgvs, UavClockRequest, UavClockReply>;

inline constexpr std::size_t kTopicCount = std::tuple_size_v<Messages>;

// A topic: the index of its message in Messages.
enum class Topic : std::uint8_t {};

namespace detail {
template <class Msg, class List>
struct IndexOf;
template <class Msg, class... Ms>
struct IndexOf<Msg, std::tuple<Ms...>> {
  static constexpr std::size_t value = [] {
    constexpr bool same[] = {std::is_same_v<Msg, Ms>...};
    for (std::size_t i = 0; i < sizeof...(Ms); ++i)
      if (same[i]) return i;
    return sizeof...(Ms);
  }();
};
}  // namespace detail

template <class Msg>
inline constexpr Topic topic_of = [] {
  constexpr std::size_t i = detail::IndexOf<Msg, Messages>::value;
  static_assert(i < kTopicCount, "not a message of msg::Messages");
  return static_cast<Topic>(i);
}();

template <std::size_t I>
using MessageAt = std::tuple_element_t<I, Messages>;

struct TopicInfo {
  Topic topic;
  const char* name;        // DDS topic name
  std::size_t size_bytes;  // sizeof the message struct
  Reliability reliability;
  std::uint16_t history_depth;  // keep-last depth per key (robot)
  Duration deadline;            // expected max gap between samples of one key; 0 = none
  Delivery delivery;
};

inline constexpr std::array<TopicInfo, kTopicCount> kTopicTable =
    []<std::size_t... I>(std::index_sequence<I...>) {
  return std::array<TopicInfo, kTopicCount>{
      TopicInfo{static_cast<Topic>(I), kTopicSpec<MessageAt<I>>.name, sizeof(MessageAt<I>),
                kTopicSpec<MessageAt<I>>.reliability, kTopicSpec<MessageAt<I>>.history_depth,
                kTopicSpec<MessageAt<I>>.deadline, kTopicSpec<MessageAt<I>>.delivery}...};
}
(std::make_index_sequence<kTopicCount>{});

constexpr const TopicInfo& topic_info(Topic t) {
  return kTopicTable[static_cast<std::size_t>(t)];
}

// Message type -> topic, and the key (robot id) each sample is filed under.
template <class Msg>
struct MessageTraits {
  static constexpr Topic kTopic = topic_of<Msg>;
  static RobotId key(const Msg& m) { return m.*kTopicSpec<Msg>.key; }
};

// Calls f.template operator()<Msg>() with the message type of `topic`, for code that handles
// samples type-erased (transports): `visit_message_type(t, [&]<class Msg>() { ... });`. A topic
// out of range is taken as the last one: check the range first where it comes from outside.
template <std::size_t I = 0, class F>
decltype(auto) visit_message_type(Topic topic, F&& f) {
  if constexpr (I + 1 < kTopicCount) {
    if (static_cast<std::size_t>(topic) != I) return visit_message_type<I + 1>(topic, f);
  }
  return f.template operator()<MessageAt<I>>();
}

// Calls f.template operator()<Msg>() for every message type, in topic order.
template <class F>
void for_each_message_type(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f.template operator()<MessageAt<I>>(), ...);
  }
  (std::make_index_sequence<kTopicCount>{});
}

// The key of a type-erased sample; `sample` must point to the topic's message struct.
inline RobotId message_key(Topic topic, const void* sample) {
  return visit_message_type(topic, [&]<class Msg>() {
    return MessageTraits<Msg>::key(*static_cast<const Msg*>(sample));
  });
}

// The bytes a type-erased sample puts on the wire (wire_size.hpp).
inline std::size_t message_wire_bytes(Topic topic, const void* sample) {
  return visit_message_type(
      topic, [&]<class Msg>() { return wire_bytes(*static_cast<const Msg*>(sample)); });
}

// The largest message, for transports that hold samples in fixed slots.
inline constexpr std::size_t kMaxMessageBytes = [] {
  std::size_t m = 0;
  for (const auto& t : kTopicTable)
    m = t.size_bytes > m ? t.size_bytes : m;
  return m;
}();

// Messages are plain structs: copied as bytes by the transports.
static_assert([]<std::size_t... I>(std::index_sequence<I...>) {
  return (
      (std::is_trivially_copyable_v<MessageAt<I>> && std::is_standard_layout_v<MessageAt<I>>)&&...);
}(std::make_index_sequence<kTopicCount>{}));

}  // namespace colag::msg
