#include "colag/uav/separation.hpp"

#include <algorithm>
#include <cmath>

namespace colag::uav {

namespace {
// The unit vector along `away` (of length d); on top of each other any direction apart will do,
// the same one every step.
Vec2 direction(const Vec2& away, double d) {
  return d > 1e-6 ? Vec2(away / d) : Vec2(1.0, 0.0);
}
}  // namespace

Vec2 Neighbour::nearest(const Vec2& q) const {
  const Vec2 line = p_end - p;
  const double l2 = line.squaredNorm();
  if (l2 < 1e-12) return p;
  return p + std::clamp((q - p).dot(line) / l2, 0.0, 1.0) * line;
}

Vec2 separate(const Vec2& p, const Vec2& wanted, const Neighbours& others, double v_max,
              const SeparationConfig& config) {
  Vec2 v = wanted;
  // A few passes: a correction for one neighbour can break the condition of another.
  for (int pass = 0; pass < 3; ++pass) {
    bool changed = false;
    for (const Neighbour& o : others) {
      const Vec2 away = p - o.nearest(p);
      const double d = away.norm();
      const Vec2 n = direction(away, d);
      const double share = o.cooperates ? 0.5 : 1.0;
      // Lower bound on the speed away from it; one that does not cooperate moves on its own.
      const double gap = d - config.min_m;
      double bound = gap >= 0.0 ? -std::min(std::sqrt(2.0 * share * config.brake_mps2 * gap),
                                            share * config.rate_per_s * gap)
                                : -config.out_rate_per_s * gap;
      if (!o.cooperates) bound += n.dot(o.v);
      const double missing = bound - n.dot(v);
      if (missing <= 1e-9) continue;
      // The speed taken away goes sideways, the way the UAV already slides past it: against
      // that way it cancelled the slide and held the UAV at the keep-out's edge for good (a dead
      // UAV between it and its stop). Head-on, to the right of the line towards it (-n).
      const Vec2 right(-n.y(), n.x());
      const Vec2 side = v.dot(right) < -1e-6 ? Vec2(-right) : right;
      v += missing * n + (pass == 0 ? config.sidestep * missing : 0.0) * side;
      changed = true;
    }
    if (!changed) break;
  }
  const double speed = v.norm();
  if (speed > v_max) v *= v_max / speed;
  return v;
}

Vec2 clear_of(const Vec2& point, const Neighbours& others, double radius) {
  Vec2 q = point;
  for (int pass = 0; pass < 3; ++pass) {
    for (const Neighbour& o : others) {
      if (o.cooperates) continue;
      const Vec2 at = o.nearest(q);
      const Vec2 away = q - at;
      const double d = away.norm();
      if (d >= radius) continue;
      q = at + radius * direction(away, d);
    }
  }
  return q;
}

}  // namespace colag::uav
