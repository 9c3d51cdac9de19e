#pragma once
// The robot-to-robot topics: one table with each topic's name and quality of service, used by
// every transport (the DDS transport creates its topics and QoS from it), and the static
// mapping from message type to topic and key.
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "colag/common/time.hpp"
#include "colag/msg/collision_info.hpp"
#include "colag/msg/map_patch.hpp"
#include "colag/msg/relative_pose.hpp"
#include "colag/msg/support_plan.hpp"
#include "colag/msg/uav_odometry.hpp"
#include "colag/msg/ugv_status.hpp"

namespace colag::msg {

enum class Topic : std::uint8_t {
  kUavOdometry,
  kRelativePose,
  kMapPatch,
  kCollisionInfo,
  kUgvStatus,
  kSupportPlan,
};
inline constexpr std::size_t kTopicCount = 6;

enum class Reliability : std::uint8_t { kBestEffort, kReliable };

struct TopicInfo {
  Topic topic;
  const char* name;        // DDS topic name
  std::size_t size_bytes;  // sizeof the message struct
  Reliability reliability;
  std::uint16_t history_depth;  // keep-last depth per key (robot)
  Duration deadline;            // expected max gap between samples of one key; 0 = none
};

// Why these QoS: odometry is high-rate and superseded quickly (best effort, a short history so
// the UGV can match RPE stamps); RPE, map patches, requests and plans must arrive (reliable);
// CollisionInfo keeps only the latest per UGV, so a cancel always supersedes its request.
inline constexpr std::array<TopicInfo, kTopicCount> kTopicTable = {{
    {Topic::kUavOdometry, "colag_uav_odometry", sizeof(UavOdometry), Reliability::kBestEffort, 16,
     std::chrono::milliseconds(200)},
    {Topic::kRelativePose, "colag_relative_pose", sizeof(RelativePose), Reliability::kReliable, 8,
     Duration::zero()},
    {Topic::kMapPatch, "colag_map_patch", sizeof(MapPatch), Reliability::kReliable, 4,
     Duration::zero()},
    {Topic::kCollisionInfo, "colag_collision_info", sizeof(CollisionInfo), Reliability::kReliable,
     1, Duration::zero()},
    {Topic::kUgvStatus, "colag_ugv_status", sizeof(UgvStatus), Reliability::kBestEffort, 4,
     std::chrono::milliseconds(500)},
    {Topic::kSupportPlan, "colag_support_plan", sizeof(SupportPlan), Reliability::kReliable, 1,
     Duration::zero()},
}};

constexpr const TopicInfo& topic_info(Topic t) {
  return kTopicTable[static_cast<std::size_t>(t)];
}

// Message type -> topic, and the key (robot id) each sample is filed under.
template <class Msg>
struct MessageTraits;

template <>
struct MessageTraits<UavOdometry> {
  static constexpr Topic kTopic = Topic::kUavOdometry;
  static RobotId key(const UavOdometry& m) { return m.uav_id; }
};
template <>
struct MessageTraits<RelativePose> {
  static constexpr Topic kTopic = Topic::kRelativePose;
  static RobotId key(const RelativePose& m) { return m.ugv_id; }  // the UGV it is about
};
template <>
struct MessageTraits<MapPatch> {
  static constexpr Topic kTopic = Topic::kMapPatch;
  static RobotId key(const MapPatch& m) { return m.ugv_id; }  // the UGV it is for
};
template <>
struct MessageTraits<CollisionInfo> {
  static constexpr Topic kTopic = Topic::kCollisionInfo;
  static RobotId key(const CollisionInfo& m) { return m.ugv_id; }
};
template <>
struct MessageTraits<UgvStatus> {
  static constexpr Topic kTopic = Topic::kUgvStatus;
  static RobotId key(const UgvStatus& m) { return m.ugv_id; }
};
template <>
struct MessageTraits<SupportPlan> {
  static constexpr Topic kTopic = Topic::kSupportPlan;
  static RobotId key(const SupportPlan& m) { return m.uav_id; }
};

// Calls f.template operator()<Msg>() with the message type of `topic`, for code that handles
// samples type-erased (transports): `visit_message_type(t, [&]<class Msg>() { ... });`
template <class F>
decltype(auto) visit_message_type(Topic topic, F&& f) {
  switch (topic) {
    case Topic::kUavOdometry:
      return f.template operator()<UavOdometry>();
    case Topic::kRelativePose:
      return f.template operator()<RelativePose>();
    case Topic::kMapPatch:
      return f.template operator()<MapPatch>();
    case Topic::kCollisionInfo:
      return f.template operator()<CollisionInfo>();
    case Topic::kUgvStatus:
      return f.template operator()<UgvStatus>();
    case Topic::kSupportPlan:
      break;
  }
  return f.template operator()<SupportPlan>();
}

// The key of a type-erased sample; `sample` must point to the topic's message struct.
inline RobotId message_key(Topic topic, const void* sample) {
  return visit_message_type(topic, [&]<class Msg>() {
    return MessageTraits<Msg>::key(*static_cast<const Msg*>(sample));
  });
}

// The largest message, for transports that hold samples in fixed slots.
inline constexpr std::size_t kMaxMessageBytes = [] {
  std::size_t m = 0;
  for (const auto& t : kTopicTable)
    m = t.size_bytes > m ? t.size_bytes : m;
  return m;
}();

template <class Msg>
inline constexpr bool kIsMessage =
    std::is_trivially_copyable_v<Msg>&& std::is_standard_layout_v<Msg>&& topic_info(
        MessageTraits<Msg>::kTopic)
        .size_bytes
    == sizeof(Msg);

static_assert(
    [] {
      for (std::size_t i = 0; i < kTopicCount; ++i) {
        if (static_cast<std::size_t>(kTopicTable[i].topic) != i) return false;
      }
      return true;
    }(),
    "kTopicTable must list the topics in enum order");
static_assert(kIsMessage<UavOdometry> && kIsMessage<RelativePose> && kIsMessage<MapPatch> &&
              kIsMessage<CollisionInfo> && kIsMessage<UgvStatus> && kIsMessage<SupportPlan>);

}  // namespace colag::msg
