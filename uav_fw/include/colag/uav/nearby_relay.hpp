#pragma once
// The UGVs' statuses go to the UAV only (their own DDS partitions); each UGV learns from the
// UAV which other UGVs are near enough to plan around: a list per UGV, every 100 ms, with every
// UGV that may be within the list's radius (a silent one as far as it can have driven since it
// was last heard), nearest first. What each UGV receives then depends on its neighbourhood, not
// on the size of the fleet.
//
// In a crowd the lists are most of a UGV's traffic (32 UGVs in the dense 27 m site: 5.9 of its
// 8.9 kB/s, twelve entries a list), and most entries are UGVs several metres away, which change
// what it plans far less than the one beside it. So only every `full_every`-th pass lists all
// within `radius_m`; the passes between list those within `near_radius_m`, and the UGV keeps
// what it heard of the farther ones from the last full list (ugv_nav_task.cpp,
// read_other_ugvs). A list's radius_m is where it is complete: a list cut at kMaxNearbyUgvs
// says so by a smaller radius (the first UGV left out), so that no UGV takes an absence from a
// full list for "farther".
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "colag/common/geometry.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/nearby_ugvs.hpp"

namespace colag::uav {

struct NearbyRelayConfig {
  double radius_m = 12.0;  // > a UGV's planning range (6 m) + its 3 sigma cap (2 m) + margin
  // The lists between full ones: the UGVs that can reach this one within ~3 s at the speed
  // limit (both driving), more than its collision prediction's 2 m horizon plus two bodies.
  double near_radius_m = 6.0;
  int full_every = 2;  // 1: every list is full
  double ugv_max_speed_mps = 0.7;
};

// The radius of pass `pass` of the relay (0, 1, 2, ...): full every `full_every`-th.
inline double nearby_radius(const NearbyRelayConfig& config, std::uint64_t pass) {
  const auto every = static_cast<std::uint64_t>(std::max(config.full_every, 1));
  return pass % every == 0 ? config.radius_m : std::min(config.near_radius_m, config.radius_m);
}

// Fills `out`'s list for UGV `to` from `ugvs` (indexed by id; each with .known, .heard and
// .status: its latest msg::UgvStatus), the UGVs within `radius_m`; the caller sets the header.
// Allocates nothing.
template <class Ugvs>
void fill_nearby(RobotId to, const Ugvs& ugvs, TimePoint now, const NearbyRelayConfig& config,
                 double radius_m, msg::NearbyUgvs& out) {
  out.ugv_id = to;
  out.radius_m = radius_m;
  out.ugvs.count = 0;
  const auto& me = ugvs[to].status;
  const Vec2 here(me.position_m[0], me.position_m[1]);
  StaticVector<std::pair<double, RobotId>, limits::kMaxUgvs> near;
  for (std::size_t id = 0; id < ugvs.size(); ++id) {
    const auto& u = ugvs[id];
    if (id == to || !u.known) continue;
    const double silent_s = std::max(to_seconds(now - u.heard), 0.0);
    const double d = (Vec2(u.status.position_m[0], u.status.position_m[1]) - here).norm();
    // Sorted by how near it may be now: the list is complete within its radius.
    const double nearest = d - config.ugv_max_speed_mps * silent_s;
    if (nearest > radius_m) continue;
    (void)near.push_back({nearest, static_cast<RobotId>(id)});
  }
  std::sort(near.begin(), near.end());
  for (const auto& [d, id] : near) {
    if (out.ugvs.count == out.ugvs.capacity()) {
      out.radius_m = std::max(d, 0.0);  // complete up to the first left out
      break;
    }
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
// stamped `now`, through `publish(out)` (true when sent); returns how many were sent. Pass
// number `pass` of the relay (see nearby_radius).
template <class Ugvs, class Mine, class Publish>
int relay_nearby(const Ugvs& ugvs, TimePoint now, Duration timeout, const NearbyRelayConfig& config,
                 std::uint64_t pass, msg::NearbyUgvs& out, Mine&& mine, Publish&& publish) {
  int sent = 0;
  const double radius_m = nearby_radius(config, pass);
  for (std::size_t to = 0; to < ugvs.size(); ++to) {
    if (!ugvs[to].known || now - ugvs[to].heard > timeout) continue;
    if (!mine(static_cast<RobotId>(to))) continue;
    fill_nearby(static_cast<RobotId>(to), ugvs, now, config, radius_m, out);
    out.stamp = now;
    ++out.seq;
    sent += publish(out) ? 1 : 0;
  }
  return sent;
}

// ... to every UGV heard.
template <class Ugvs, class Publish>
int relay_nearby(const Ugvs& ugvs, TimePoint now, Duration timeout, const NearbyRelayConfig& config,
                 std::uint64_t pass, msg::NearbyUgvs& out, Publish&& publish) {
  return relay_nearby(
      ugvs, now, timeout, config, pass, out, [](RobotId) { return true; },
      std::forward<Publish>(publish));
}

}  // namespace colag::uav
