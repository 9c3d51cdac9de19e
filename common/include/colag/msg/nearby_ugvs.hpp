#pragma once
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/sequence.hpp"
#include "colag/msg/topic.hpp"
#include "colag/msg/ugv_status.hpp"

namespace colag::msg {

// What a UGV needs of another UGV to plan around it: from that UGV's latest status.
struct NearbyUgv {
  // Single precision (48 bytes on the wire instead of 96: a UGV's list is most of its traffic
  // in a crowded fleet). float32 holds a position 1 km away to 0.06 mm, far below the pose's
  // own uncertainty.
  TimePoint stamp;  // the status's stamp (fleet time)
  RobotId ugv_id = 0;
  UgvMode mode = UgvMode::kWaitingForInit;
  float position_m[2] = {};
  float yaw_rad = 0.0F;
  float covariance_xy[3] = {};  // (xx, xy, yy) of its position, m^2
  float velocity_mps = 0.0F;
  float yaw_rate_radps = 0.0F;
  // How long before this message's stamp the UAV last heard it (the UAV's clock): a UGV that
  // went silent may have driven on since, at its speed limit.
  float silent_s = 0.0F;
  friend bool operator==(const NearbyUgv&, const NearbyUgv&) = default;
};
COLAG_MESSAGE_FIELDS(NearbyUgv, stamp, ugv_id, mode, position_m, yaw_rad, covariance_xy,
                     velocity_mps, yaw_rate_radps, silent_s);

// UAV -> one UGV, 10 Hz: every other UGV within radius_m of it that the UAV hears, nearest
// first (at most kMaxNearbyUgvs). The list is complete within the radius: a UGV not in it is
// farther. The radius alternates (12 m, then 6 m: see uav/nearby_relay.hpp), and a list cut at
// kMaxNearbyUgvs carries the distance of the first UGV left out; a UGV beyond a list's radius
// is neither confirmed nor denied by it. The UGVs do not read each other's statuses (they would
// grow every UGV's traffic with the fleet); the UAV hears them all and relays to each UGV the few
// it must plan around.
struct NearbyUgvs {
  TimePoint stamp;
  RobotId uav_id = 0;
  RobotId ugv_id = 0;  // destination
  std::uint32_t seq = 0;
  double radius_m = 0.0;
  Sequence<NearbyUgv, limits::kMaxNearbyUgvs> ugvs;
  friend bool operator==(const NearbyUgvs&, const NearbyUgvs&) = default;
};
COLAG_MESSAGE_FIELDS(NearbyUgvs, stamp, uav_id, ugv_id, seq, radius_m, ugvs);

// Superseded 100 ms later: best effort, the newest only. Filed under its destination.
template <>
inline constexpr TopicSpec<NearbyUgvs> kTopicSpec<NearbyUgvs> = {
    "colag_nearby_ugvs", &NearbyUgvs::ugv_id, Reliability::kBestEffort, 1,
    Duration::zero(),    Delivery::kPerUgv};

}  // namespace colag::msg
