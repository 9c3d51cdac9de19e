#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "colag/common/ellipse.hpp"
#include "colag/common/random.hpp"

using namespace colag;

namespace {

// Exact oracle: the square [x0,x1]x[y0,y1] meets the ellipse iff the minimum of the quadratic
// form over the square is <= 1. The minimum is at the centre (if inside) or on an edge.
bool square_meets_ellipse(const Ellipse& e, double x0, double y0, double x1, double y1) {
  const Vec2 c = e.center;
  if (c.x() >= x0 && c.x() <= x1 && c.y() >= y0 && c.y() <= y1) return true;
  const Mat2 A = e.M.inverse();
  const auto q = [&](const Vec2& p) { return (p - c).dot(A * (p - c)); };
  const auto edge_min = [&](const Vec2& a, const Vec2& b) {
    const Vec2 d = b - a;
    const double denom = d.dot(A * d);
    double t = denom > 0 ? -(a - c).dot(A * d) / denom : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return q(a + t * d);
  };
  const Vec2 p00(x0, y0), p10(x1, y0), p01(x0, y1), p11(x1, y1);
  const double m =
      std::min({edge_min(p00, p10), edge_min(p10, p11), edge_min(p11, p01), edge_min(p01, p00)});
  return m <= 1.0 + 1e-12;
}

std::set<std::pair<int, int>> rasterised(const GridGeometry2d& g, const Ellipse& e) {
  std::set<std::pair<int, int>> cells;
  any_cell_touching(g, e, [&](CellIndex c) {
    EXPECT_TRUE(cells.insert({c.x, c.y}).second) << "cell visited twice";
    return false;
  });
  return cells;
}

std::set<std::pair<int, int>> brute_force(const GridGeometry2d& g, const Ellipse& e) {
  std::set<std::pair<int, int>> cells;
  for (int j = 0; j < g.cells_y(); ++j) {
    for (int i = 0; i < g.cells_x(); ++i) {
      const double x0 = g.origin_x() + i * g.resolution(), y0 = g.origin_y() + j * g.resolution();
      if (square_meets_ellipse(e, x0, y0, x0 + g.resolution(), y0 + g.resolution()))
        cells.insert({i, j});
    }
  }
  return cells;
}

}  // namespace

TEST(Ellipse, RasterisationEqualsTheExactOracleOnRandomEllipses) {
  const GridGeometry2d g(-3.0, -2.0, 0.1, 60, 50);
  Rng rng(77);
  for (int trial = 0; trial < 400; ++trial) {
    // Random orientation, axes from 1 mm to 1.5 m (thin, round, tiny), centre anywhere, also
    // partly outside the grid.
    const double angle = rng.uniform(0, M_PI);
    const double s1 = std::exp(rng.uniform(std::log(0.001), std::log(0.5)));
    const double s2 = std::exp(rng.uniform(std::log(0.001), std::log(0.5)));
    const Mat2 R = rotation2(angle);
    const Mat2 cov = R * Vec2(s1 * s1, s2 * s2).asDiagonal() * R.transpose();
    const Vec2 mean(rng.uniform(-3.5, 3.5), rng.uniform(-2.5, 3.5));
    const Ellipse e = sigma_ellipse(mean, cov);
    ASSERT_EQ(rasterised(g, e), brute_force(g, e)) << "trial " << trial;
  }
}

TEST(Ellipse, AZeroCovarianceTouchesExactlyItsOwnCell) {
  const GridGeometry2d g(0.0, 0.0, 0.1, 20, 20);
  const auto cells = rasterised(g, sigma_ellipse(Vec2(0.53, 1.27), Mat2::Zero()));
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(*cells.begin(), std::make_pair(5, 12));
}

TEST(Ellipse, StopsAtTheFirstHit) {
  const GridGeometry2d g(0.0, 0.0, 0.1, 20, 20);
  int visits = 0;
  const bool hit = any_cell_touching(g, sigma_ellipse(Vec2(1, 1), Mat2::Identity() * 0.01),
                                     [&](CellIndex) { return ++visits == 3; });
  EXPECT_TRUE(hit);
  EXPECT_EQ(visits, 3);
}

TEST(Ellipse, AxesAreThreeSigma) {
  const Mat2 R = rotation2(0.4);
  const Mat2 cov = R * Vec2(0.25, 0.04).asDiagonal() * R.transpose();
  const Ellipse e = sigma_ellipse(Vec2(1, 2), cov);
  const auto ax = e.axes();
  EXPECT_NEAR(ax.a_m, 1.5, 1e-9);
  EXPECT_NEAR(ax.b_m, 0.6, 1e-9);
  EXPECT_NEAR(std::cos(2 * (ax.angle_rad - 0.4)), 1.0, 1e-9);  // direction up to sign
  EXPECT_TRUE(e.contains(Vec2(1, 2) + R * Vec2(1.49, 0)));
  EXPECT_FALSE(e.contains(Vec2(1, 2) + R * Vec2(0, 0.61)));
}
