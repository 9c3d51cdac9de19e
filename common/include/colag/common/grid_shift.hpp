#pragma once
// Moving a fixed-size grid window over a larger site, in place: the cells both windows hold keep
// their values, the cells that enter take `fill`. Used by the UGV's 2-D map and the UAV's 3-D
// map (layer by layer): no second buffer, so the window costs no more memory than the grid.
#include <algorithm>
#include <cstddef>
#include <cstdlib>

namespace colag {

// `cells` is an nx x ny row-major layer (x fastest). Afterwards new cell (x, y) holds what old
// cell (x + dx, y + dy) held, or `fill` where that was outside.
template <class T>
void shift_layer(T* cells, int nx, int ny, int dx, int dy, const T& fill) {
  if (dx == 0 && dy == 0) return;
  const auto row = [&](int y) { return cells + static_cast<std::ptrdiff_t>(y) * nx; };
  // Rows in the order that never overwrites a row still to be read; within a row std::copy or
  // std::copy_backward by the same rule.
  for (int k = 0; k < ny; ++k) {
    const int y = dy >= 0 ? k : ny - 1 - k;
    const int from_y = y + dy;
    T* const out = row(y);
    if (from_y < 0 || from_y >= ny || std::abs(dx) >= nx) {
      std::fill(out, out + nx, fill);
      continue;
    }
    const T* const in = row(from_y);
    if (dx >= 0) {
      std::copy(in + dx, in + nx, out);  // out <= in: forward is safe
      std::fill(out + (nx - dx), out + nx, fill);
    } else {
      std::copy_backward(in, in + (nx + dx), out + nx);
      std::fill(out, out - dx, fill);
    }
  }
}

}  // namespace colag
