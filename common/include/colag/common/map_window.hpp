#pragma once
// Where a robot's map window should be. The maps are fixed-size grids (limits.hpp) that move
// over a site of any size, on the grid's lattice (grid_shift.hpp moves the cells). These are the
// rules for when and where to move one, and for planning towards a destination it does not hold.
#include <optional>

#include "colag/common/geometry.hpp"
#include "colag/common/grid2d.hpp"
#include "colag/common/status.hpp"

namespace colag {

struct WindowPolicy {
  // With the destination outside the window, the window moves once the robot is this close to
  // an edge (it then leads towards the destination: the robot keeps this much behind it and
  // the rest ahead). With the destination inside, it moves only at `hard_edge_m`.
  double edge_m = 8.0;
  double hard_edge_m = 1.0;
};

// The whole cells (dx, dy) a window at g moves to put its origin at `origin`; refused when
// `origin` is not finite, not on g's lattice, or absurdly far (beyond 1000 km).
Status window_step(const GridGeometry2d& g, const Vec2& origin, int& dx, int& dy);

// How far p is inside the window: the distance to its nearest edge (negative outside).
double inset_in(const GridGeometry2d& g, const Vec2& p);

// The origin on g's lattice (a whole number of cells from g's) that puts the window's centre
// nearest to `centre`.
Vec2 origin_centred_at(const GridGeometry2d& g, const Vec2& centre);

// Where the window of a robot at `at`, heading for `toward` (if it has a destination), should
// have its origin; nothing when it should stay (or would land where it is). With a destination:
// moved, it holds both when they are close enough to both lie edge_m inside, else the robot edge_m
// + 1 m from the trailing side, towards `toward`. Without (the UAV, which flies everywhere): it
// moves along each axis where the robot is within hard_edge_m of an edge, just enough that it is
// edge_m inside.
std::optional<Vec2> window_move(const GridGeometry2d& g, const Vec2& at,
                                const std::optional<Vec2>& toward, const WindowPolicy& policy);

// The point furthest along the segment from -> to that lies margin_m inside the window (`to`
// itself when it does): where to plan towards a destination the window does not hold. When
// `from` itself is not that far inside, `to` is clamped into the shrunk window.
Vec2 clip_into(const GridGeometry2d& g, const Vec2& from, const Vec2& to, double margin_m);

}  // namespace colag
