#pragma once
// Message struct <-> IDL sample conversion, both ways, for every topic. to_idl() fills an
// IdlSample that may borrow the message's buffers (keep the message alive while the sample is
// used); from_idl() rejects what the message struct cannot hold (oversized sequences, enum
// values out of range) and leaves semantic checks (NaN, stale stamps) to the receiving task.
#include "colag/common/status.hpp"
#include "colag/msg/topics.hpp"
#include "collision_info.h"
#include "map_patch.h"
#include "relative_pose.h"
#include "support_plan.h"
#include "uav_odometry.h"
#include "ugv_status.h"

namespace colag::platform::dds {

template <class Msg>
struct IdlSample;

// A sample plus the storage its sequences point into; not copyable (it points into itself).
template <class Idl>
struct IdlSampleBase {
  IdlSampleBase() = default;
  IdlSampleBase(const IdlSampleBase&) = delete;
  IdlSampleBase& operator=(const IdlSampleBase&) = delete;
  Idl sample{};
};

template <>
struct IdlSample<msg::UavOdometry> : IdlSampleBase<colag_idl_UavOdometry> {
  using Type = colag_idl_UavOdometry;
};
template <>
struct IdlSample<msg::RelativePose> : IdlSampleBase<colag_idl_RelativePose> {
  using Type = colag_idl_RelativePose;
};
template <>
struct IdlSample<msg::MapPatch> : IdlSampleBase<colag_idl_MapPatch> {
  using Type = colag_idl_MapPatch;  // data borrows msg::MapPatch::data
};
template <>
struct IdlSample<msg::CollisionInfo> : IdlSampleBase<colag_idl_CollisionInfo> {
  using Type = colag_idl_CollisionInfo;
};
template <>
struct IdlSample<msg::UgvStatus> : IdlSampleBase<colag_idl_UgvStatus> {
  using Type = colag_idl_UgvStatus;
};
template <>
struct IdlSample<msg::SupportPlan> : IdlSampleBase<colag_idl_SupportPlan> {
  using Type = colag_idl_SupportPlan;
  colag_idl_SupportStop stops[limits::kMaxSupportRequests]{};
};

void to_idl(const msg::UavOdometry& in, IdlSample<msg::UavOdometry>& out);
void to_idl(const msg::RelativePose& in, IdlSample<msg::RelativePose>& out);
void to_idl(const msg::MapPatch& in, IdlSample<msg::MapPatch>& out);
void to_idl(const msg::CollisionInfo& in, IdlSample<msg::CollisionInfo>& out);
void to_idl(const msg::UgvStatus& in, IdlSample<msg::UgvStatus>& out);
void to_idl(const msg::SupportPlan& in, IdlSample<msg::SupportPlan>& out);

Status from_idl(const colag_idl_UavOdometry& in, msg::UavOdometry& out);
Status from_idl(const colag_idl_RelativePose& in, msg::RelativePose& out);
Status from_idl(const colag_idl_MapPatch& in, msg::MapPatch& out);
Status from_idl(const colag_idl_CollisionInfo& in, msg::CollisionInfo& out);
Status from_idl(const colag_idl_UgvStatus& in, msg::UgvStatus& out);
Status from_idl(const colag_idl_SupportPlan& in, msg::SupportPlan& out);

// The generated type descriptor of each message's IDL mirror.
template <class Msg>
const dds_topic_descriptor_t& descriptor();

}  // namespace colag::platform::dds
