#pragma once
// Exact traversal of the grid cells a segment passes through (Amanatides-Woo), in order.
// Where the segment passes exactly through a cell corner, both side cells are visited too, so
// "no visited cell is blocked" really means the segment touches no blocked cell.
#include <cmath>
#include <limits>

#include "colag/common/grid2d.hpp"

namespace colag {

// Calls visit(CellIndex) for each cell; stops and returns true as soon as visit returns true.
template <class Visit>
bool any_cell_on_segment(const GridGeometry2d& g, const Vec2& a, const Vec2& b, Visit&& visit) {
  CellIndex c = g.cell_of(a);
  const CellIndex end = g.cell_of(b);
  if (visit(c)) return true;
  const Vec2 d = b - a;
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double res = g.resolution();
  const auto first_crossing = [&](double p, double dp, double origin, int cell, int step) {
    if (dp == 0.0) return kInf;
    const double boundary = origin + (cell + (step > 0 ? 1 : 0)) * res;
    return (boundary - p) / dp;
  };
  double t_max_x = first_crossing(a.x(), d.x(), g.origin_x(), c.x, sx);
  double t_max_y = first_crossing(a.y(), d.y(), g.origin_y(), c.y, sy);
  const double t_dx = d.x() != 0.0 ? res / std::abs(d.x()) : kInf;
  const double t_dy = d.y() != 0.0 ? res / std::abs(d.y()) : kInf;
  // Bounded by the Manhattan distance in cells (+2 for rounding at the ends).
  int steps = std::abs(end.x - c.x) + std::abs(end.y - c.y) + 2;
  while (!(c == end) && steps-- > 0) {
    if (std::abs(t_max_x - t_max_y) < 1e-12) {
      if (t_max_x > 1.0) break;
      // Through a corner: the two side cells are touched.
      if (visit(CellIndex{c.x + sx, c.y}) || visit(CellIndex{c.x, c.y + sy})) return true;
      c.x += sx;
      c.y += sy;
      t_max_x += t_dx;
      t_max_y += t_dy;
    } else if (t_max_x < t_max_y) {
      if (t_max_x > 1.0) break;
      c.x += sx;
      t_max_x += t_dx;
    } else {
      if (t_max_y > 1.0) break;
      c.y += sy;
      t_max_y += t_dy;
    }
    if (visit(c)) return true;
  }
  return false;
}

}  // namespace colag
