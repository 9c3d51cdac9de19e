#include "colag/ugv/trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace colag::ugv {

namespace {

// One piece of the rounded path: a segment (radius 0) or an arc.
struct Piece {
  Vec2 start = Vec2::Zero();
  double heading = 0.0;  // at the start
  double length = 0.0;
  double curvature = 0.0;      // signed, 1/m
  bool stop_at_start = false;  // a corner too sharp to round: turn on the spot
};

Vec2 advance(const Piece& p, double s, double& heading) {
  if (p.curvature == 0.0) {
    heading = p.heading;
    return p.start + s * Vec2(std::cos(p.heading), std::sin(p.heading));
  }
  const double r = 1.0 / p.curvature;
  heading = p.heading + s * p.curvature;
  // Circle centre to the left (k > 0) or right (k < 0) of the start heading.
  const Vec2 centre = p.start + r * Vec2(-std::sin(p.heading), std::cos(p.heading));
  return centre + r * Vec2(std::sin(heading), -std::cos(heading));
}

}  // namespace

bool Trajectory::build(const Path& path, double v0, const TrajectoryLimits& lim) {
  samples_.clear();
  const auto& w = path.waypoints;
  if (w.empty()) return false;

  // 1. Segments between consecutive distinct waypoints, then a fillet at each inner corner.
  StaticVector<Piece, 2 * limits::kMaxWaypoints> pieces;
  StaticVector<Vec2, limits::kMaxWaypoints> pts;
  for (const Vec2& p : w) {
    if (pts.empty() || (p - pts.back()).norm() > 1e-6) (void)pts.push_back(p);
  }
  if (pts.size() == 1) {
    TrajectorySample s;
    s.p = pts[0];
    (void)samples_.push_back(s);
    return true;
  }
  Vec2 cursor = pts[0];
  bool sharp_corner = false;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Vec2 dir = (pts[i + 1] - pts[i]).normalized();
    const double heading = std::atan2(dir.y(), dir.x());
    double seg_end_cut = 0.0;  // part of this segment eaten by the next fillet
    Piece arc;
    bool has_arc = false;
    double turn = 0.0;
    if (i + 2 < pts.size()) {
      const Vec2 next = (pts[i + 2] - pts[i + 1]).normalized();
      turn = wrap_angle(std::atan2(next.y(), next.x()) - heading);
      const double half = std::abs(turn) / 2.0;
      if (half > 1e-4 && half < M_PI / 2 - 1e-3) {
        // Deviation of an arc of radius R from its corner: R (1/cos(half) - 1).
        double radius = lim.corner_deviation_m / (1.0 / std::cos(half) - 1.0);
        const double room =
            0.5 * std::min((pts[i + 1] - pts[i]).norm(), (pts[i + 2] - pts[i + 1]).norm());
        radius = std::min(radius, room / std::tan(half));
        const double tangent = radius * std::tan(half);
        seg_end_cut = tangent;
        arc.start = pts[i + 1] - tangent * dir;
        arc.heading = heading;
        arc.length = radius * std::abs(turn);
        arc.curvature = (turn > 0 ? 1.0 : -1.0) / radius;
        has_arc = arc.length > 1e-9;
      }
    }
    Piece line;
    line.start = cursor;
    line.heading = heading;
    line.stop_at_start = sharp_corner;
    line.length = std::max(0.0, (pts[i + 1] - cursor).norm() - seg_end_cut);
    if (line.length > 1e-9) (void)pieces.push_back(line);
    if (has_arc) {
      (void)pieces.push_back(arc);
      double h = 0;
      cursor = advance(arc, arc.length, h);
    } else {
      cursor = pts[i + 1];
    }
    sharp_corner = !has_arc && std::abs(turn) > 0.05;
  }

  // 2. Sample every spacing_m (and at the very end).
  double s_total = 0.0;
  for (const Piece& p : pieces) {
    for (double s = 0.0; s < p.length - 1e-9; s += lim.spacing_m) {
      TrajectorySample ts;
      ts.s_m = s_total + s;
      ts.p = advance(p, s, ts.yaw_rad);
      ts.yaw_rad = wrap_angle(ts.yaw_rad);
      ts.curvature = p.curvature;
      if (s == 0.0 && p.stop_at_start) ts.v_mps = -1.0;  // marks a forced stop (see below)
      if (!samples_.push_back(ts)) break;
    }
    s_total += p.length;
    if (samples_.full()) break;
  }
  if (!samples_.full() && !pieces.empty()) {
    TrajectorySample ts;
    ts.s_m = s_total;
    ts.p = advance(pieces.back(), pieces.back().length, ts.yaw_rad);
    ts.yaw_rad = wrap_angle(ts.yaw_rad);
    (void)samples_.push_back(ts);
  }
  const bool cut = samples_.full();

  // 3. Speed profile: curvature limit, then acceleration limits both ways.
  const std::size_t n = samples_.size();
  for (auto& s : samples_) {
    const bool forced_stop = s.v_mps < 0.0;
    s.v_mps = forced_stop ? 0.0 : lim.v_max_mps;
    if (s.curvature != 0.0)
      s.v_mps = std::min(s.v_mps, lim.omega_max_radps / std::abs(s.curvature));
  }
  samples_[0].v_mps = std::clamp(v0, 0.0, samples_[0].v_mps);
  for (std::size_t i = 1; i < n; ++i) {
    const double ds = samples_[i].s_m - samples_[i - 1].s_m;
    samples_[i].v_mps = std::min(
        samples_[i].v_mps,
        std::sqrt(samples_[i - 1].v_mps * samples_[i - 1].v_mps + 2 * lim.a_max_mps2 * ds));
  }
  if (!cut) samples_[n - 1].v_mps = 0.0;  // rest at the goal (a cut plan keeps going)
  for (std::size_t i = n - 1; i-- > 0;) {
    const double ds = samples_[i + 1].s_m - samples_[i].s_m;
    samples_[i].v_mps = std::min(
        samples_[i].v_mps,
        std::sqrt(samples_[i + 1].v_mps * samples_[i + 1].v_mps + 2 * lim.a_max_mps2 * ds));
  }
  // 4. Time stamps (constant acceleration between samples) and yaw rates.
  for (std::size_t i = 1; i < n; ++i) {
    const double ds = samples_[i].s_m - samples_[i - 1].s_m;
    const double v_sum = samples_[i].v_mps + samples_[i - 1].v_mps;
    samples_[i].t_s = samples_[i - 1].t_s + (v_sum > 1e-9 ? 2.0 * ds / v_sum : 0.0);
  }
  for (auto& s : samples_)
    s.omega_radps = s.v_mps * s.curvature;
  return true;
}

std::size_t Trajectory::index_at_time(double t_s, std::size_t from) const {
  std::size_t i = std::min(from, samples_.empty() ? 0 : samples_.size() - 1);
  while (i + 1 < samples_.size() && samples_[i].t_s < t_s)
    ++i;
  return i;
}

}  // namespace colag::ugv
