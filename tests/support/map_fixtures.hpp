#pragma once
// Test helper: fills a UGV MapStore through real, encoded map patches (so the codec and the
// patch validation are exercised too), from a function giving each cell's state.
#include <algorithm>
#include <functional>

#include "colag/common/map_patch_codec.hpp"
#include "colag/common/map_store.hpp"

namespace colag::test {

// Applies patches covering the cells of [x0, x1) x [y0, y1) (world metres).
inline bool fill_map(MapStore& map, double x0, double y0, double x1, double y1,
                     const std::function<CellState(const Vec2&)>& state_at, RobotId uav = 0) {
  const auto& g = map.geometry();
  const CellIndex c0 = g.cell_of(Vec2(x0 + 1e-9, y0 + 1e-9));
  const CellIndex c1 = g.cell_of(Vec2(x1 - 1e-9, y1 - 1e-9));
  const int side = limits::kMaxPatchSideCells;
  for (int by = c0.y; by <= c1.y; by += side) {
    for (int bx = c0.x; bx <= c1.x; bx += side) {
      PatchCells cells;
      cells.width = std::min(side, c1.x - bx + 1);
      cells.height = std::min(side, c1.y - by + 1);
      for (int y = 0; y < cells.height; ++y) {
        for (int x = 0; x < cells.width; ++x) {
          cells.cells[static_cast<std::size_t>(y) * cells.width + x] =
              state_at(g.center_of({bx + x, by + y}));
        }
      }
      msg::MapPatch patch;
      if (!encode_patch(cells, patch)) return false;
      patch.resolution_m = g.resolution();
      patch.uav_id = uav;
      const Vec2 corner = g.center_of({bx, by}) - Vec2::Constant(0.5 * g.resolution());
      patch.origin_x_m = corner.x();
      patch.origin_y_m = corner.y();
      if (!map.apply(patch)) return false;
    }
  }
  return true;
}

inline std::function<CellState(const Vec2&)> all_free() {
  return [](const Vec2&) { return CellState::kFree; };
}

}  // namespace colag::test
