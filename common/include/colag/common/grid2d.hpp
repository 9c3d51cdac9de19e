#pragma once
// Geometry of a 2-D grid: world <-> cell conversions. Cell (i, j) covers
// [ox + i*res, ox + (i+1)*res) x [oy + j*res, oy + (j+1)*res). Storage is the user's
// (fixed arrays sized from limits.hpp), indexed row-major by index().
#include <cmath>
#include <cstddef>

#include "colag/common/geometry.hpp"
#include "colag/common/limits.hpp"

namespace colag {

// floor(x) as an int, without a libm call (the baseline x86-64 target has no rounding
// instruction) and without undefined behaviour: x is clamped to +-1e9 first (NaN gives -1e9).
constexpr int floor_to_int(double x) {
  x = x > -1e9 ? (x < 1e9 ? x : 1e9) : -1e9;
  const int i = static_cast<int>(x);
  return i - (static_cast<double>(i) > x ? 1 : 0);
}

struct CellIndex {
  int x = 0;
  int y = 0;
  friend bool operator==(const CellIndex&, const CellIndex&) = default;
};

class GridGeometry2d {
 public:
  constexpr GridGeometry2d(double origin_x_m, double origin_y_m, double resolution_m, int cells_x,
                           int cells_y)
      : ox_(origin_x_m),
        oy_(origin_y_m),
        res_(resolution_m),
        inv_res_(1.0 / resolution_m),
        nx_(cells_x),
        ny_(cells_y) {}

  constexpr double resolution() const { return res_; }
  constexpr double origin_x() const { return ox_; }
  constexpr double origin_y() const { return oy_; }
  constexpr int cells_x() const { return nx_; }
  constexpr int cells_y() const { return ny_; }
  constexpr std::size_t size() const { return static_cast<std::size_t>(nx_) * ny_; }

  constexpr bool contains(CellIndex c) const {
    return c.x >= 0 && c.y >= 0 && c.x < nx_ && c.y < ny_;
  }
  bool contains(const Vec2& p) const { return contains(cell_of(p)); }
  CellIndex cell_of(const Vec2& p) const {
    return {floor_to_int((p.x() - ox_) * inv_res_), floor_to_int((p.y() - oy_) * inv_res_)};
  }
  Vec2 center_of(CellIndex c) const { return {ox_ + (c.x + 0.5) * res_, oy_ + (c.y + 0.5) * res_}; }
  constexpr std::size_t index(CellIndex c) const {
    return static_cast<std::size_t>(c.y) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(c.x);
  }
  constexpr CellIndex cell_at(std::size_t index) const {
    return {static_cast<int>(index % static_cast<std::size_t>(nx_)),
            static_cast<int>(index / static_cast<std::size_t>(nx_))};
  }

 private:
  double ox_, oy_, res_, inv_res_;  // multiply, don't divide: cell_of is hot
  int nx_, ny_;
};

// The world grid every robot shares (extent and resolution from limits.hpp).
inline constexpr GridGeometry2d kWorldGrid2d{limits::kGridOriginX_m, limits::kGridOriginY_m,
                                             limits::kGridResolution_m, limits::kGridCellsX,
                                             limits::kGridCellsY};
static_assert(kWorldGrid2d.size() == limits::kGridCells2d);

}  // namespace colag
