#pragma once
// The UGVs' statuses go to the UAV only (their own DDS partitions); each UGV learns from the
// UAV which other UGVs are near enough to plan around: a list per UGV, every 100 ms, with every
// UGV that may be within the radius (a silent one as far as it can have driven since it was
// last heard), nearest first. What each UGV receives then depends on its neighbourhood, not on
// the size of the fleet.
#include <algorithm>
#include <cmath>
#include <utility>

#include "colag/common/geometry.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/nearby_ugvs.hpp"

namespace colag::uav {

struct NearbyRelayConfig {
  double radius_m = 12.0;  // > a UGV's planning range (6 m) + its 3 sigma cap (2 m) + margin
  double ugv_max_speed_mps = 0.7;
};

// Fills `out`'s list for UGV `to` from `ugvs` (indexed by id; each with .known, .heard and
// .status: its latest msg::UgvStatus); the caller sets the header. Allocates nothing.
template <class Ugvs>
void fill_nearby(RobotId to, const Ugvs& ugvs, TimePoint now, const NearbyRelayConfig& config,
                 msg::NearbyUgvs& out) {
  out.ugv_id = to;
  out.radius_m = config.radius_m;
  out.ugvs.count = 0;
  const auto& me = ugvs[to].status;
  const Vec2 here(me.position_m[0], me.position_m[1]);
  StaticVector<std::pair<double, RobotId>, limits::kMaxUgvs> near;
  for (std::size_t id = 0; id < ugvs.size(); ++id) {
    const auto& u = ugvs[id];
    if (id == to || !u.known) continue;
    const double silent_s = std::max(to_seconds(now - u.heard), 0.0);
    const double d = (Vec2(u.status.position_m[0], u.status.position_m[1]) - here).norm();
    if (d - config.ugv_max_speed_mps * silent_s > config.radius_m) continue;
    (void)near.push_back({d, static_cast<RobotId>(id)});
  }
  std::sort(near.begin(), near.end());
  for (const auto& [d, id] : near) {
    if (out.ugvs.count == out.ugvs.capacity()) break;
    const auto& u = ugvs[id];
    msg::NearbyUgv& n = out.ugvs[out.ugvs.count++];
    n.stamp = u.status.stamp;
    n.ugv_id = id;
    n.mode = u.status.mode;
    const auto f = [](double v) { return static_cast<float>(v); };
    n.position_m[0] = f(u.status.position_m[0]);
    n.position_m[1] = f(u.status.position_m[1]);
    n.yaw_rad = f(u.status.yaw_rad);
    n.covariance_xy[0] = f(u.status.covariance[0]);
    n.covariance_xy[1] = f(u.status.covariance[1]);
    n.covariance_xy[2] = f(u.status.covariance[4]);
    n.velocity_mps = f(u.status.velocity_mps);
    n.yaw_rate_radps = f(u.status.yaw_rate_radps);
    n.silent_s = f(std::max(to_seconds(now - u.heard), 0.0));
  }
}

// Every UGV heard within `timeout` for which `mine(id)` holds gets its list (fill_nearby),
// stamped `now`, through `publish(out)` (true when sent); returns how many were sent. One pass of
// the relay.
template <class Ugvs, class Mine, class Publish>
int relay_nearby(const Ugvs& ugvs, TimePoint now, Duration timeout, const NearbyRelayConfig& config,
                 msg::NearbyUgvs& out, Mine&& mine, Publish&& publish) {
  int sent = 0;
  for (std::size_t to = 0; to < ugvs.size(); ++to) {
    if (!ugvs[to].known || now - ugvs[to].heard > timeout) continue;
    if (!mine(static_cast<RobotId>(to))) continue;
    fill_nearby(static_cast<RobotId>(to), ugvs, now, config, out);
    out.stamp = now;
    ++out.seq;
    sent += publish(out) ? 1 : 0;
  }
  return sent;
}

// ... to every UGV heard.
template <class Ugvs, class Publish>
int relay_nearby(const Ugvs& ugvs, TimePoint now, Duration timeout, const NearbyRelayConfig& config,
                 msg::NearbyUgvs& out, Publish&& publish) {
  return relay_nearby(
      ugvs, now, timeout, config, out, [](RobotId) { return true; },
      std::forward<Publish>(publish));
}

}  // namespace colag::uav
