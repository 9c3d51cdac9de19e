#pragma once
// Keeps the UAVs of a fleet apart (beyond the paper, which flies one UAV). A filter on the
// horizontal velocity the flight planner wants: towards each other UAV, the UAV may close in no
// faster than it can brake to a stand at min_m, sqrt(2 brake (distance - min_m)), and within a
// metre of it no faster than rate_per_s x (distance - min_m) (a control-barrier condition: the
// distance tends to min_m and does not cross it); nothing changes far away. brake is a quarter of
// the UAV's a_max: the rest is room for what the condition does not see (the line to the other
// turning as they pass, its position a step old, the setpoint ramp). A peer that flies the mission
// brakes for the other half (each brakes within half the distance); one that does not answer
// (silent, landing, in a pilot's hands) is kept clear of alone. Closer than min_m (a peer appeared
// there), it moves away at out_rate_per_s x the shortfall. Part of the approach speed taken away
// is turned sideways, the way the UAV already passes the other (to the right of the line to it
// when head-on): two UAVs head-on both turn right and pass instead of stopping nose to nose, and
// one whose stop lies behind a dead UAV slides round it instead of waiting at its edge.
#include "colag/common/geometry.hpp"
#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"

namespace colag::uav {

struct SeparationConfig {
  double min_m = 1.5;        // centre to centre, horizontal: rotors, downwash and GNSS-free drift
  double brake_mps2 = 0.25;  // of the UAV's a_max (1 m/s^2); 0.7 let two come 0.6 m close
  double rate_per_s = 1.0;
  double out_rate_per_s = 0.5;
  double sidestep = 0.5;  // of the approach speed taken away, this much turned sideways
  // Round a UAV that does not cooperate, beyond min_m: a target is moved this far out of its
  // keep-out, and the flight path keeps this far (less, so a moved target is not inside it).
  double target_margin_m = 0.5;
  double path_margin_m = 0.2;
};

struct Neighbour {
  Vec2 p = Vec2::Zero();
  Vec2 v = Vec2::Zero();
  bool cooperates = false;  // flies the mission and keeps to its half
  // Where it is not known exactly (silent since p): somewhere on the line from p to p_end.
  Vec2 p_end = p;
  Vec2 nearest(const Vec2& q) const;  // its point nearest to q
};
using Neighbours = StaticVector<Neighbour, limits::kMaxUavs>;

// The velocity closest in spirit to `wanted` that keeps the separation from every neighbour,
// no faster than v_max.
Vec2 separate(const Vec2& p, const Vec2& wanted, const Neighbours& others, double v_max,
              const SeparationConfig& config);

// A point to fly to, moved out to `radius` from each neighbour that does not cooperate (a dead
// UAV hovering over a support point): the closest place its own keep-out leaves.
Vec2 clear_of(const Vec2& point, const Neighbours& others, double radius);

}  // namespace colag::uav
