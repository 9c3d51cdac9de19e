#pragma once
// Geometry of the 3-D voxel grid (the UAV's map): world <-> voxel, row-major index with x
// fastest, then y, then z (one horizontal layer is contiguous).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "colag/common/geometry.hpp"
#include "colag/common/grid2d.hpp"
#include "colag/common/limits.hpp"

namespace colag {

struct VoxelIndex {
  int x = 0, y = 0, z = 0;
  friend bool operator==(const VoxelIndex&, const VoxelIndex&) = default;
};

class GridGeometry3d {
 public:
  constexpr GridGeometry3d(double ox, double oy, double oz, double res, int nx, int ny, int nz)
      : ox_(ox), oy_(oy), oz_(oz), res_(res), inv_res_(1.0 / res), nx_(nx), ny_(ny), nz_(nz) {}

  constexpr double resolution() const { return res_; }
  constexpr double origin_x() const { return ox_; }
  constexpr double origin_y() const { return oy_; }
  constexpr double origin_z() const { return oz_; }
  constexpr int cells_x() const { return nx_; }
  constexpr int cells_y() const { return ny_; }
  constexpr int cells_z() const { return nz_; }
  constexpr std::size_t size() const { return static_cast<std::size_t>(nx_) * ny_ * nz_; }
  // The same x/y layout as a 2-D grid (each layer).
  constexpr GridGeometry2d layer() const { return {ox_, oy_, res_, nx_, ny_}; }

  constexpr bool contains(VoxelIndex v) const {
    return v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < nx_ && v.y < ny_ && v.z < nz_;
  }
  VoxelIndex voxel_of(const Vec3& p) const {
    return {floor_to_int((p.x() - ox_) * inv_res_), floor_to_int((p.y() - oy_) * inv_res_),
            floor_to_int((p.z() - oz_) * inv_res_)};
  }
  Vec3 center_of(VoxelIndex v) const {
    return {ox_ + (v.x + 0.5) * res_, oy_ + (v.y + 0.5) * res_, oz_ + (v.z + 0.5) * res_};
  }
  constexpr std::size_t index(VoxelIndex v) const {
    return (static_cast<std::size_t>(v.z) * static_cast<std::size_t>(ny_) +
            static_cast<std::size_t>(v.y)) *
               static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(v.x);
  }

 private:
  double ox_, oy_, oz_, res_, inv_res_;  // multiply, don't divide: voxel_of is hot
  int nx_, ny_, nz_;
};

// A layer of voxels a traversal stops in front of: those whose index along `axis` (0 x, 1 y,
// 2 z) is `cell`. No axis: no such layer.
struct VoxelLayer {
  int axis = -1;
  int cell = 0;
};

// Exact traversal (Amanatides-Woo) of the voxels the segment a -> b passes through, in order,
// from a's voxel (which must be inside the grid) to b's voxel, or until the segment leaves the
// grid or would step into `stop` (when a is not in it). Calls visit(linear index); stops early
// and returns true when visit returns true.
// The hot loop of the UAV's mapper: the linear index is stepped incrementally and the number
// of steps is known up front, so each step is a comparison, two adds and the visit.
template <class Visit>
bool any_voxel_index_on_segment(const GridGeometry3d& g, const Vec3& a, const Vec3& b,
                                VoxelLayer stop, Visit&& visit) {
  const VoxelIndex v0 = g.voxel_of(a), v1 = g.voxel_of(b);
  const Vec3 d = b - a;
  const double res = g.resolution();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Per axis: the voxel stride in memory, the ray parameter t of the next boundary crossing,
  // the t between crossings, and how many crossings remain before the grid's edge. Scalars,
  // not arrays, so that the loop keeps them in registers.
  struct Axis {
    std::ptrdiff_t step;
    double t_next, t_delta;
    int room;
  };
  const auto axis = [&](double dk, double ak, double origin, int cell, int size,
                        std::ptrdiff_t stride) {
    if (dk == 0.0) return Axis{0, kInf, kInf, 0};
    const bool up = dk > 0;
    const double inv = 1.0 / dk;  // one division per axis and ray
    return Axis{up ? stride : -stride, (origin + (cell + (up ? 1 : 0)) * res - ak) * inv,
                res * std::abs(inv), up ? size - 1 - cell : cell};
  };
  Axis x = axis(d.x(), a.x(), g.origin_x(), v0.x, g.cells_x(), 1);
  Axis y = axis(d.y(), a.y(), g.origin_y(), v0.y, g.cells_y(), g.cells_x());
  Axis z = axis(d.z(), a.z(), g.origin_z(), v0.z, g.cells_z(),
                static_cast<std::ptrdiff_t>(g.cells_x()) * g.cells_y());
  // Stopping in front of a layer is running out of room towards it one cell early: no
  // division for where the segment meets it.
  const auto limit = [&](Axis& k, int cell) {
    if (k.step == 0 || cell == stop.cell) return;
    if ((k.step > 0) == (stop.cell > cell))
      k.room = std::min(k.room, std::abs(stop.cell - cell) - 1);
  };
  if (stop.axis == 0) limit(x, v0.x);
  if (stop.axis == 1) limit(y, v0.y);
  if (stop.axis == 2) limit(z, v0.z);
  // Voxels to visit after the first: the steps to b's voxel (fewer if the grid ends first).
  int budget = std::abs(v1.x - v0.x) + std::abs(v1.y - v0.y) + std::abs(v1.z - v0.z);
  std::ptrdiff_t i = static_cast<std::ptrdiff_t>(g.index(v0));
  const auto advance = [&](Axis& k) {
    if (k.t_next > 1.0 || k.room-- == 0) return false;  // past b (rounding) or out of the grid
    i += k.step;
    k.t_next += k.t_delta;
    return true;
  };
  // One call site of visit, so that the compiler inlines it into the loop (with two, GCC kept
  // the mapper's visit out of line: a call and its captures reloaded at every voxel).
  for (;; --budget) {
    if (visit(static_cast<std::size_t>(i))) return true;
    if (budget == 0) return false;
    const bool moved = x.t_next < y.t_next ? (x.t_next < z.t_next ? advance(x) : advance(z))
                                           : (y.t_next < z.t_next ? advance(y) : advance(z));
    if (!moved) return false;
  }
}

template <class Visit>
bool any_voxel_index_on_segment(const GridGeometry3d& g, const Vec3& a, const Vec3& b,
                                Visit&& visit) {
  return any_voxel_index_on_segment(g, a, b, VoxelLayer{}, std::forward<Visit>(visit));
}

// The same traversal, visiting VoxelIndex values (tests, tools).
template <class Visit>
bool any_voxel_on_segment(const GridGeometry3d& g, const Vec3& a, const Vec3& b, Visit&& visit) {
  const std::size_t layer =
      static_cast<std::size_t>(g.cells_x()) * static_cast<std::size_t>(g.cells_y());
  return any_voxel_index_on_segment(g, a, b, [&](std::size_t i) {
    const std::size_t xy = i % layer;
    return visit(VoxelIndex{static_cast<int>(xy % static_cast<std::size_t>(g.cells_x())),
                            static_cast<int>(xy / static_cast<std::size_t>(g.cells_x())),
                            static_cast<int>(i / layer)});
  });
}

inline constexpr GridGeometry3d kWorldGrid3d{limits::kGridOriginX_m, limits::kGridOriginY_m,
                                             limits::kGridOriginZ_m, limits::kGridResolution_m,
                                             limits::kGridCellsX,    limits::kGridCellsY,
                                             limits::kGridCellsZ};
static_assert(kWorldGrid3d.size() == limits::kGridCells3d);

}  // namespace colag
