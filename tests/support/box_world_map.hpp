#pragma once
// Test helper: what a UGV's map looks like when the UAV has mapped a box world perfectly
// inside a window: cells overlapping a box footprint are occupied, the rest of the window is
// free, everything outside it stays unknown.
#include "colag/sim/world/box_world.hpp"
#include "map_fixtures.hpp"

namespace colag::test {

inline bool fill_map_from_world(MapStore& map, const sim::BoxWorld& world, double x0, double y0,
                                double x1, double y1) {
  const double h = 0.5 * map.geometry().resolution();
  return fill_map(map, x0, y0, x1, y1, [&](const Vec2& p) {
    for (const auto& b : world.boxes) {
      const Vec2 d = (p - b.center).cwiseAbs();
      if (d.x() < b.half_size.x() + h && d.y() < b.half_size.y() + h) return CellState::kOccupied;
    }
    return CellState::kFree;
  });
}

}  // namespace colag::test
