#pragma once
// k-sigma ellipses of a 2-D Gaussian and their exact rasterisation on a grid: the cells whose
// square intersects the ellipse (not just the cells whose centre is inside, which would miss
// cells under a thin ellipse and every cell under a point-like one).
#include <algorithm>
#include <cmath>

#include "colag/common/geometry.hpp"
#include "colag/common/grid2d.hpp"

namespace colag {

// The points p with (p - centre)^T M^-1 (p - centre) <= 1, M = k^2 * covariance.
struct Ellipse {
  Vec2 center = Vec2::Zero();
  Mat2 M = Mat2::Zero();

  // Semi-axes a >= b (a = k*sqrt(lambda1), b = k*sqrt(lambda2)) and the direction of a.
  struct Axes {
    double a_m, b_m, angle_rad;
  };
  Axes axes() const;
  bool contains(const Vec2& p) const;
  // The ellipse with both semi-axes longer by m >= 0 (same centre and directions): it contains
  // every point within m of this one.
  Ellipse grown(double m) const;
};

// M is floored to a tiny positive definite matrix so a zero covariance is a point, not NaN.
Ellipse sigma_ellipse(const Vec2& mean, const Mat2& covariance, double k_sigma = 3.0);

// Calls visit(CellIndex) for every in-grid cell whose square intersects the ellipse, row by
// row from the bottom; stops as soon as visit returns true and returns true in that case.
template <class Visit>
bool any_cell_touching(const GridGeometry2d& grid, const Ellipse& e, Visit&& visit) {
  const double res = grid.resolution();
  const double m11 = e.M(0, 0), m12 = e.M(0, 1), m22 = e.M(1, 1);
  const double hy = std::sqrt(m22);  // half height of the ellipse
  const double hx = std::sqrt(m11);  // half width
  const double slope = m12 / m22;    // chord centre moves by slope * dy
  const double chord = std::sqrt(std::max(0.0, m11 - m12 * m12 / m22));  // half chord at dy=0
  const double y_right = m12 / hx;  // dy of the rightmost point
  // x-extent of the ellipse over the horizontal strip dy in [lo, hi] (relative to the centre).
  const auto strip_extent = [&](double lo, double hi, double& xmin, double& xmax) {
    const auto half = [&](double dy) {
      return chord * std::sqrt(std::max(0.0, 1.0 - dy * dy / m22));
    };
    const double r_dy = std::clamp(y_right, lo, hi);   // right(dy) is concave: max at y_right
    const double l_dy = std::clamp(-y_right, lo, hi);  // left(dy) is convex: min at -y_right
    xmax = slope * r_dy + half(r_dy);
    xmin = slope * l_dy - half(l_dy);
  };
  const int j0 =
      std::max(0, static_cast<int>(std::floor((e.center.y() - hy - grid.origin_y()) / res)));
  const int j1 =
      std::min(grid.cells_y() - 1,
               static_cast<int>(std::floor((e.center.y() + hy - grid.origin_y()) / res)));
  for (int j = j0; j <= j1; ++j) {
    const double y0 = grid.origin_y() + j * res - e.center.y();
    const double lo = std::max(y0, -hy), hi = std::min(y0 + res, hy);
    if (lo > hi) continue;
    double xmin = 0, xmax = 0;
    strip_extent(lo, hi, xmin, xmax);
    const int i0 =
        std::max(0, static_cast<int>(std::floor((e.center.x() + xmin - grid.origin_x()) / res)));
    const int i1 =
        std::min(grid.cells_x() - 1,
                 static_cast<int>(std::floor((e.center.x() + xmax - grid.origin_x()) / res)));
    for (int i = i0; i <= i1; ++i) {
      if (visit(CellIndex{i, j})) return true;
    }
  }
  return false;
}

}  // namespace colag
