#include "colag/sim/world/cloud_world.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace colag::sim {

namespace {

constexpr double kMaxCoordinate_m = 1e6;  // parse_pcd refuses farther points; skip them here

bool usable(const Vec3& p) {
  return all_finite(p) && p.cwiseAbs().maxCoeff() <= kMaxCoordinate_m;
}

// The k-th smallest of `v` (reorders it).
double nth(std::vector<double>& v, std::size_t k) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

double median(std::vector<double>& v) {
  return nth(v, v.size() / 2);
}

// One 0.1 m column of obstacle points: heights above the ground, and where its points lie.
struct Column {
  double low, top;
  Vec2 lo, hi;
};

// What a column is to a UGV, quantised so that neighbours with the same extent merge: its base
// (0 standing on the ground) and its top, in centimetres.
using Extent = std::pair<long, long>;

}  // namespace

GroundFit fit_ground(const std::vector<Vec3>& points) {
  std::vector<double> z;
  z.reserve(points.size());
  for (const Vec3& p : points) {
    if (usable(p)) z.push_back(p.z());
  }
  GroundFit fit;
  if (z.empty()) return fit;
  // Near the bottom of the cloud (its 1st percentile, so that a few stray points below the
  // ground do not count), the most populated 1 cm height bin; the lowest one on a tie.
  const double bottom = nth(z, z.size() / 100);
  constexpr double kBin = 0.01, kSpan = 0.4, kNear = 0.05;
  std::vector<std::size_t> bins(static_cast<std::size_t>(kSpan / kBin), 0);
  for (const double v : z) {
    const double k = std::floor((v - bottom + 0.5 * kBin) / kBin);
    if (k >= 0.0 && k < static_cast<double>(bins.size())) ++bins[static_cast<std::size_t>(k)];
  }
  const auto mode = std::max_element(bins.begin(), bins.end()) - bins.begin();
  const double guess = bottom + static_cast<double>(mode) * kBin;
  std::vector<double> near;
  for (const double v : z) {
    if (std::abs(v - guess) <= kNear) near.push_back(v);
  }
  fit.points = near.size();
  fit.z_m = median(near);
  for (double& v : near)
    v = std::abs(v - fit.z_m);
  fit.sigma_m = 1.4826 * median(near);
  return fit;
}

BoxWorld box_world_from_points(const std::vector<Vec3>& points, const CloudWorldConfig& config,
                               CloudWorldReport* report) {
  CloudWorldReport rep;
  rep.ground = fit_ground(points);
  const double ground = rep.ground.z_m;
  const double noise_floor = std::max(0.03, 4.0 * rep.ground.sigma_m);
  const double res = config.resolution_m;

  BoxWorld world;
  // Each column's obstacle points. A point on a cell boundary (a box whose points lie on whole
  // multiples of 0.1 m) belongs to the cell above it, within rounding.
  std::map<std::pair<long, long>, Column> columns;  // (y, x): row by row
  double min_x = 1e18, max_x = -1e18, min_y = 1e18, max_y = -1e18;
  for (const Vec3& p : points) {
    if (!usable(p)) continue;
    min_x = std::min(min_x, p.x());
    max_x = std::max(max_x, p.x());
    min_y = std::min(min_y, p.y());
    max_y = std::max(max_y, p.y());
    const double h = p.z() - ground;
    if (h <= noise_floor) continue;
    const std::pair<long, long> c{std::lround(std::floor(p.y() / res + 1e-6)),
                                  std::lround(std::floor(p.x() / res + 1e-6))};
    const Vec2 xy = p.head<2>();
    auto [it, inserted] = columns.try_emplace(c, Column{h, h, xy, xy});
    if (!inserted) {
      Column& col = it->second;
      col.low = std::min(col.low, h);
      col.top = std::max(col.top, h);
      col.lo = col.lo.cwiseMin(xy);
      col.hi = col.hi.cwiseMax(xy);
    }
  }
  if (min_x <= max_x) {
    world.min_x_m = min_x;
    world.max_x_m = max_x;
    world.min_y_m = min_y;
    world.max_y_m = max_y;
    rep.extent_m = Vec2(max_x - min_x, max_y - min_y);
  }

  // Runs of equal extent along each row, extended by an equal run (same cells, same extent) of
  // the row before; each rectangle keeps its points' bounds and its highest point.
  struct Rect {
    long x0, x1, last_row;
    Extent extent;
    double base, top;
    Vec2 lo, hi;
  };
  std::vector<Rect> rects;
  std::map<std::tuple<long, long, Extent>, std::size_t> open;  // runs of the previous row
  std::map<std::tuple<long, long, Extent>, std::size_t> next;
  const auto cm = [](double v) { return std::lround(std::ceil(v * 100.0 - 1e-6)); };
  const auto extent_of = [&](const Column& col, double& base) {
    base = col.low > config.band_high_m ? col.low - 0.5 * res : 0.0;  // overhead, or standing
    return Extent{cm(base), cm(col.top)};
  };
  long row = 0;
  bool first = true;
  for (auto it = columns.begin(); it != columns.end();) {
    if (it->first.first != row || first) {
      if (!first && it->first.first != row + 1) next.clear();  // a gap: nothing continues
      open.swap(next);
      next.clear();
      row = it->first.first;
      first = false;
    }
    // The run starting here: consecutive columns of this row with the same extent.
    const Column& head = it->second;
    if (head.top < config.band_low_m - 1e-6) {  // clutter a UGV drives over
      ++rep.clutter_columns;
      ++it;
      continue;
    }
    double base = 0.0;
    const Extent ext = extent_of(head, base);
    const long x0 = it->first.second;
    long x1 = x0;
    double top = head.top;
    Vec2 lo = head.lo, hi = head.hi;
    ++rep.obstacle_columns;
    for (++it; it != columns.end() && it->first.first == row && it->first.second == x1 + 1; ++it) {
      double b = 0.0;
      if (it->second.top < config.band_low_m - 1e-6 || extent_of(it->second, b) != ext) break;
      ++x1;
      ++rep.obstacle_columns;
      top = std::max(top, it->second.top);
      lo = lo.cwiseMin(it->second.lo);
      hi = hi.cwiseMax(it->second.hi);
    }
    const auto key = std::make_tuple(x0, x1, ext);
    if (auto o = open.find(key); o != open.end()) {
      Rect& r = rects[o->second];
      r.last_row = row;
      r.top = std::max(r.top, top);
      r.lo = r.lo.cwiseMin(lo);
      r.hi = r.hi.cwiseMax(hi);
      next[key] = o->second;
      open.erase(o);
    } else {
      next[key] = rects.size();
      rects.push_back({x0, x1, row, ext, base, top, lo, hi});
    }
  }
  // The obstacle reaches half a point spacing past its outermost points (the points sample the
  // centres of its surface cells); an edge within float rounding of a cell boundary is that
  // boundary (the paper's maps: points at cell centres, stored as floats).
  const auto edge = [&](double v) {
    const double k = std::round(v / res);
    return std::abs(v / res - k) < 1e-3 ? k * res : v;
  };
  for (const Rect& r : rects) {
    const Vec2 lo(edge(r.lo.x() - res / 2), edge(r.lo.y() - res / 2));
    const Vec2 hi(edge(r.hi.x() + res / 2), edge(r.hi.y() + res / 2));
    world.boxes.push_back({0.5 * (lo + hi), 0.5 * (hi - lo), r.top, r.base});
    if (r.base > 0.0) ++rep.overhead_boxes;
  }
  if (report != nullptr) *report = rep;
  return world;
}

}  // namespace colag::sim
