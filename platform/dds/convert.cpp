#include "colag/platform/dds/convert.hpp"

#include <algorithm>
#include <cstring>

namespace colag::platform::dds {

static_assert(colag_idl_MAP_PATCH_MAX_BYTES == limits::kMaxPatchBytes,
              "map_patch.idl bound must equal limits::kMaxPatchBytes");
static_assert(colag_idl_SUPPORT_PLAN_MAX_STOPS == limits::kMaxSupportRequests,
              "support_plan.idl bound must equal limits::kMaxSupportRequests");

namespace {

template <class T, std::size_t N>
void copy(const T (&from)[N], T (&to)[N]) {
  std::copy(from, from + N, to);
}

}  // namespace

// --- UavOdometry --------------------------------------------------------------------------------
void to_idl(const msg::UavOdometry& in, IdlSample<msg::UavOdometry>& out) {
  auto& s = out.sample;
  s.stamp_ns = to_nanoseconds(in.stamp);
  s.uav_id = in.uav_id;
  copy(in.position_m, s.position_m);
  copy(in.orientation_wxyz, s.orientation_wxyz);
  copy(in.velocity_mps, s.velocity_mps);
  s.yaw_rate_radps = in.yaw_rate_radps;
}
Status from_idl(const colag_idl_UavOdometry& in, msg::UavOdometry& out) {
  out.stamp = time_at_nanoseconds(in.stamp_ns);
  out.uav_id = in.uav_id;
  copy(in.position_m, out.position_m);
  copy(in.orientation_wxyz, out.orientation_wxyz);
  copy(in.velocity_mps, out.velocity_mps);
  out.yaw_rate_radps = in.yaw_rate_radps;
  return Status::ok();
}

// --- RelativePose -------------------------------------------------------------------------------
void to_idl(const msg::RelativePose& in, IdlSample<msg::RelativePose>& out) {
  auto& s = out.sample;
  s.stamp_ns = to_nanoseconds(in.stamp);
  s.uav_id = in.uav_id;
  s.ugv_id = in.ugv_id;
  copy(in.position_m, s.position_m);
  copy(in.orientation_wxyz, s.orientation_wxyz);
  copy(in.covariance, s.covariance);
}
Status from_idl(const colag_idl_RelativePose& in, msg::RelativePose& out) {
  out.stamp = time_at_nanoseconds(in.stamp_ns);
  out.uav_id = in.uav_id;
  out.ugv_id = in.ugv_id;
  copy(in.position_m, out.position_m);
  copy(in.orientation_wxyz, out.orientation_wxyz);
  copy(in.covariance, out.covariance);
  return Status::ok();
}

// --- MapPatch -----------------------------------------------------------------------------------
void to_idl(const msg::MapPatch& in, IdlSample<msg::MapPatch>& out) {
  auto& s = out.sample;
  s.stamp_ns = to_nanoseconds(in.stamp);
  s.uav_id = in.uav_id;
  s.ugv_id = in.ugv_id;
  s.seq = in.seq;
  s.resolution_m = in.resolution_m;
  s.origin_x_m = in.origin_x_m;
  s.origin_y_m = in.origin_y_m;
  s.width_cells = in.width_cells;
  s.height_cells = in.height_cells;
  s.encoding = static_cast<std::uint8_t>(in.encoding);
  s.data._maximum = static_cast<std::uint32_t>(limits::kMaxPatchBytes);
  s.data._length = std::min<std::uint32_t>(in.data_bytes, s.data._maximum);
  s.data._buffer = const_cast<std::uint8_t*>(in.data);  // borrowed: DDS only reads it
  s.data._release = false;
}
Status from_idl(const colag_idl_MapPatch& in, msg::MapPatch& out) {
  if (in.data._length > limits::kMaxPatchBytes || (in.data._length > 0 && !in.data._buffer)) {
    return {Errc::kInvalidArgument, "map patch payload larger than its bound"};
  }
  if (in.encoding > static_cast<std::uint8_t>(msg::MapPatchEncoding::kRowDelta)) {
    return {Errc::kInvalidArgument, "unknown map patch encoding"};
  }
  out.stamp = time_at_nanoseconds(in.stamp_ns);
  out.uav_id = in.uav_id;
  out.ugv_id = in.ugv_id;
  out.seq = in.seq;
  out.resolution_m = in.resolution_m;
  out.origin_x_m = in.origin_x_m;
  out.origin_y_m = in.origin_y_m;
  out.width_cells = in.width_cells;
  out.height_cells = in.height_cells;
  out.encoding = static_cast<msg::MapPatchEncoding>(in.encoding);
  out.data_bytes = static_cast<std::uint16_t>(in.data._length);
  if (in.data._length > 0) std::memcpy(out.data, in.data._buffer, in.data._length);
  std::fill(out.data + in.data._length, out.data + limits::kMaxPatchBytes, std::uint8_t{0});
  return Status::ok();
}

// --- CollisionInfo ------------------------------------------------------------------------------
void to_idl(const msg::CollisionInfo& in, IdlSample<msg::CollisionInfo>& out) {
  auto& s = out.sample;
  s.stamp_ns = to_nanoseconds(in.stamp);
  s.ugv_id = in.ugv_id;
  s.seq = in.seq;
  s.cancel = in.cancel;
  copy(in.collision_point_m, s.collision_point_m);
  copy(in.support_point_m, s.support_point_m);
  s.time_to_collision_s = in.time_to_collision_s;
}
Status from_idl(const colag_idl_CollisionInfo& in, msg::CollisionInfo& out) {
  out.stamp = time_at_nanoseconds(in.stamp_ns);
  out.ugv_id = in.ugv_id;
  out.seq = in.seq;
  out.cancel = in.cancel;
  copy(in.collision_point_m, out.collision_point_m);
  copy(in.support_point_m, out.support_point_m);
  out.time_to_collision_s = in.time_to_collision_s;
  return Status::ok();
}

// --- UgvStatus ----------------------------------------------------------------------------------
void to_idl(const msg::UgvStatus& in, IdlSample<msg::UgvStatus>& out) {
  auto& s = out.sample;
  s.stamp_ns = to_nanoseconds(in.stamp);
  s.ugv_id = in.ugv_id;
  s.mode = static_cast<std::uint8_t>(in.mode);
  copy(in.position_m, s.position_m);
  s.yaw_rad = in.yaw_rad;
  copy(in.covariance, s.covariance);
  s.velocity_mps = in.velocity_mps;
  s.yaw_rate_radps = in.yaw_rate_radps;
  copy(in.goal_m, s.goal_m);
  s.waiting_time_s = in.waiting_time_s;
  s.rejected_inputs = in.rejected_inputs;
  s.overruns = in.overruns;
  s.degradation = in.degradation;
}
Status from_idl(const colag_idl_UgvStatus& in, msg::UgvStatus& out) {
  if (in.mode > static_cast<std::uint8_t>(msg::UgvMode::kFault)) {
    return {Errc::kInvalidArgument, "unknown UGV mode"};
  }
  out.stamp = time_at_nanoseconds(in.stamp_ns);
  out.ugv_id = in.ugv_id;
  out.mode = static_cast<msg::UgvMode>(in.mode);
  copy(in.position_m, out.position_m);
  out.yaw_rad = in.yaw_rad;
  copy(in.covariance, out.covariance);
  out.velocity_mps = in.velocity_mps;
  out.yaw_rate_radps = in.yaw_rate_radps;
  copy(in.goal_m, out.goal_m);
  out.waiting_time_s = in.waiting_time_s;
  out.rejected_inputs = in.rejected_inputs;
  out.overruns = in.overruns;
  out.degradation = in.degradation;
  return Status::ok();
}

// --- SupportPlan --------------------------------------------------------------------------------
void to_idl(const msg::SupportPlan& in, IdlSample<msg::SupportPlan>& out) {
  auto& s = out.sample;
  s.stamp_ns = to_nanoseconds(in.stamp);
  s.uav_id = in.uav_id;
  s.seq = in.seq;
  s.total_lateness_s = in.total_lateness_s;
  const std::uint32_t n = std::min<std::uint32_t>(in.stop_count, limits::kMaxSupportRequests);
  for (std::uint32_t i = 0; i < n; ++i) {
    const msg::SupportStop& a = in.stops[i];
    colag_idl_SupportStop& b = out.stops[i];
    b.ugv_id = a.ugv_id;
    copy(a.point_m, b.point_m);
    b.eta_s = a.eta_s;
    b.deadline_s = a.deadline_s;
  }
  s.stops._maximum = static_cast<std::uint32_t>(limits::kMaxSupportRequests);
  s.stops._length = n;
  s.stops._buffer = out.stops;
  s.stops._release = false;
}
Status from_idl(const colag_idl_SupportPlan& in, msg::SupportPlan& out) {
  if (in.stops._length > limits::kMaxSupportRequests ||
      (in.stops._length > 0 && !in.stops._buffer)) {
    return {Errc::kInvalidArgument, "support plan longer than its bound"};
  }
  out.stamp = time_at_nanoseconds(in.stamp_ns);
  out.uav_id = in.uav_id;
  out.seq = in.seq;
  out.total_lateness_s = in.total_lateness_s;
  out.stop_count = static_cast<std::uint16_t>(in.stops._length);
  for (std::uint32_t i = 0; i < limits::kMaxSupportRequests; ++i) {
    msg::SupportStop stop{};
    if (i < in.stops._length) {
      const colag_idl_SupportStop& a = in.stops._buffer[i];
      stop.ugv_id = a.ugv_id;
      copy(a.point_m, stop.point_m);
      stop.eta_s = a.eta_s;
      stop.deadline_s = a.deadline_s;
    }
    out.stops[i] = stop;
  }
  return Status::ok();
}

// --- Descriptors --------------------------------------------------------------------------------
template <>
const dds_topic_descriptor_t& descriptor<msg::UavOdometry>() {
  return colag_idl_UavOdometry_desc;
}
template <>
const dds_topic_descriptor_t& descriptor<msg::RelativePose>() {
  return colag_idl_RelativePose_desc;
}
template <>
const dds_topic_descriptor_t& descriptor<msg::MapPatch>() {
  return colag_idl_MapPatch_desc;
}
template <>
const dds_topic_descriptor_t& descriptor<msg::CollisionInfo>() {
  return colag_idl_CollisionInfo_desc;
}
template <>
const dds_topic_descriptor_t& descriptor<msg::UgvStatus>() {
  return colag_idl_UgvStatus_desc;
}
template <>
const dds_topic_descriptor_t& descriptor<msg::SupportPlan>() {
  return colag_idl_SupportPlan_desc;
}

}  // namespace colag::platform::dds
