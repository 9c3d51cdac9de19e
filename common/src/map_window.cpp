#include "colag/common/map_window.hpp"

#include <algorithm>
#include <cmath>

namespace colag {
namespace {

struct Box {
  Vec2 lo, hi;
};

Box shrunk(const GridGeometry2d& g, double margin_m) {
  const Vec2 lo(g.origin_x(), g.origin_y());
  const Vec2 size(g.cells_x() * g.resolution(), g.cells_y() * g.resolution());
  const Vec2 m = Vec2::Constant(std::min({margin_m, 0.5 * size.x(), 0.5 * size.y()}));
  return {lo + m, lo + size - m};
}

}  // namespace

Status window_step(const GridGeometry2d& g, const Vec2& origin, int& dx, int& dy) {
  if (!all_finite(origin)) return {Errc::kInvalidArgument, "map window: origin not finite"};
  const double fx = (origin.x() - g.origin_x()) / g.resolution();
  const double fy = (origin.y() - g.origin_y()) / g.resolution();
  if (std::abs(fx) > 1e7 || std::abs(fy) > 1e7)
    return {Errc::kOutOfRange, "map window: moved beyond 1000 km"};
  if (std::abs(fx - std::round(fx)) > 1e-6 || std::abs(fy - std::round(fy)) > 1e-6)
    return {Errc::kInvalidArgument, "map window: origin not on the grid"};
  dx = static_cast<int>(std::lround(fx));
  dy = static_cast<int>(std::lround(fy));
  return Status::ok();
}

double inset_in(const GridGeometry2d& g, const Vec2& p) {
  const Box b = shrunk(g, 0.0);
  return std::min({p.x() - b.lo.x(), b.hi.x() - p.x(), p.y() - b.lo.y(), b.hi.y() - p.y()});
}

Vec2 origin_centred_at(const GridGeometry2d& g, const Vec2& centre) {
  const double res = g.resolution();
  const Vec2 want = centre - 0.5 * res * Vec2(g.cells_x(), g.cells_y());
  return {g.origin_x() + res * std::round((want.x() - g.origin_x()) / res),
          g.origin_y() + res * std::round((want.y() - g.origin_y()) / res)};
}

std::optional<Vec2> window_move(const GridGeometry2d& g, const Vec2& at,
                                const std::optional<Vec2>& toward, const WindowPolicy& policy) {
  if (!all_finite(at) || (toward && !all_finite(*toward))) return std::nullopt;
  const double inset = inset_in(g, at);
  const bool holds_destination = !toward || inset_in(g, *toward) >= 0.0;
  if (inset >= policy.hard_edge_m && (holds_destination || inset >= policy.edge_m))
    return std::nullopt;
  const Box b = shrunk(g, 0.0);
  const Vec2 size = b.hi - b.lo;
  // Where it is already (a robot standing still where rounding keeps it near the edge): stay.
  const auto same_or = [&](const Vec2& o) -> std::optional<Vec2> {
    if (std::abs(o.x() - g.origin_x()) < 0.5 * g.resolution() &&
        std::abs(o.y() - g.origin_y()) < 0.5 * g.resolution())
      return std::nullopt;
    return o;
  };
  if (!toward) {
    // Along each axis where the robot is too close to an edge: just enough that it is edge_m
    // inside (moves of several metres, and most of what the window held stays in it).
    const Vec2 keep = (Vec2::Constant(policy.edge_m)).cwiseMin(0.5 * size);
    Vec2 shift = Vec2::Zero();
    for (int k = 0; k < 2; ++k) {
      if (at[k] - b.lo[k] < policy.hard_edge_m) shift[k] = (at[k] - b.lo[k]) - keep[k];
      if (b.hi[k] - at[k] < policy.hard_edge_m) shift[k] = keep[k] - (b.hi[k] - at[k]);
    }
    return same_or(origin_centred_at(g, 0.5 * (b.lo + b.hi) + shift));
  }
  // The robot a metre more than edge_m from the trailing edge: the lattice's rounding never
  // leaves it just short of edge_m (which would move the window again at once).
  const double lead = std::max(0.5 * std::min(size.x(), size.y()) - policy.edge_m - 1.0, 0.0);
  const Vec2 d = *toward - at;
  const double n = d.norm();
  return same_or(n <= 2.0 * lead ? origin_centred_at(g, at + 0.5 * d)
                                 : origin_centred_at(g, at + (lead / n) * d));
}

Vec2 clip_into(const GridGeometry2d& g, const Vec2& from, const Vec2& to, double margin_m) {
  const Box b = shrunk(g, margin_m);
  const auto inside = [&](const Vec2& p) {
    return p.x() >= b.lo.x() && p.x() <= b.hi.x() && p.y() >= b.lo.y() && p.y() <= b.hi.y();
  };
  if (inside(to)) return to;
  if (!inside(from)) return to.cwiseMax(b.lo).cwiseMin(b.hi);
  // The segment leaves the box once: the smallest exit parameter over the two axes.
  const Vec2 d = to - from;
  double t = 1.0;
  for (int k = 0; k < 2; ++k) {
    if (d[k] > 0.0) t = std::min(t, (b.hi[k] - from[k]) / d[k]);
    if (d[k] < 0.0) t = std::min(t, (b.lo[k] - from[k]) / d[k]);
  }
  return (from + std::max(t, 0.0) * d).cwiseMax(b.lo).cwiseMin(b.hi);
}

}  // namespace colag
