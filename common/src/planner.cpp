#include "colag/common/planner.hpp"

#include <algorithm>
#include <cmath>

#include "colag/common/grid_line.hpp"

namespace colag {

namespace {
constexpr float kSqrt2 = 1.41421356F;

float octile(CellIndex a, CellIndex b) {
  const int dx = std::abs(a.x - b.x), dy = std::abs(a.y - b.y);
  return static_cast<float>(std::max(dx, dy)) +
         (kSqrt2 - 1.0F) * static_cast<float>(std::min(dx, dy));
}
}  // namespace

const char* to_string(PlanResult r) {
  switch (r) {
    case PlanResult::kOk:
      return "ok";
    case PlanResult::kNoPath:
      return "no path";
    case PlanResult::kStartBlocked:
      return "start blocked";
    case PlanResult::kGoalBlocked:
      return "goal blocked";
  }
  return "?";
}

// --- heap
// -----------------------------------------------------------------------------------------
void Planner::sift_up(std::int32_t pos) {
  const std::int32_t cell = heap_[pos];
  while (pos > 0) {
    const std::int32_t parent = (pos - 1) / 2;
    if (!before(cell, heap_[parent])) break;
    heap_[pos] = heap_[parent];
    heap_pos_[heap_[pos]] = pos;
    pos = parent;
  }
  heap_[pos] = cell;
  heap_pos_[cell] = pos;
}

void Planner::sift_down(std::int32_t pos) {
  const std::int32_t cell = heap_[pos];
  for (;;) {
    std::int32_t child = 2 * pos + 1;
    if (child >= heap_size_) break;
    if (child + 1 < heap_size_ && before(heap_[child + 1], heap_[child])) ++child;
    if (!before(heap_[child], cell)) break;
    heap_[pos] = heap_[child];
    heap_pos_[heap_[pos]] = pos;
    pos = child;
  }
  heap_[pos] = cell;
  heap_pos_[cell] = pos;
}

void Planner::heap_push(std::int32_t cell) {
  heap_[heap_size_] = cell;
  sift_up(heap_size_++);
}

void Planner::heap_decrease(std::int32_t cell) {
  sift_up(heap_pos_[cell]);
}

std::int32_t Planner::heap_pop() {
  const std::int32_t top = heap_[0];
  heap_pos_[top] = -1;  // closed
  if (--heap_size_ > 0) {
    heap_[0] = heap_[heap_size_];
    sift_down(0);
  }
  return top;
}

// --- search -------------------------------------------------------------------------------------
bool Planner::nearest_free(CellIndex from, CellIndex& out) const {
  const int r = static_cast<int>(std::ceil(config_.escape_radius_m / geometry().resolution()));
  double best = 1e18;
  bool found = false;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const CellIndex c{from.x + dx, from.y + dy};
      const double d2 = dx * dx + dy * dy;
      if (d2 > r * r || d2 >= best || blocked(c)) continue;
      best = d2;
      out = c;
      found = true;
    }
  }
  return found;
}

bool Planner::search(CellIndex start, CellIndex goal) {
  const auto& g = geometry();
  const auto s = static_cast<std::int32_t>(g.index(start));
  const auto t = static_cast<std::int32_t>(g.index(goal));
  heap_size_ = 0;
  seen_[s] = generation_;
  g_[s] = 0.0F;
  f_[s] = octile(start, goal);
  parent_[s] = kNoParent;
  heap_push(s);
  expansions_ = 0;
  while (heap_size_ > 0) {
    const std::int32_t cur = heap_pop();
    if (cur == t) return true;
    if (++expansions_ > config_.max_expansions) return false;
    const CellIndex c = g.cell_at(static_cast<std::size_t>(cur));
    bool free_side[4] = {false, false, false, false};
    for (int k = 0; k < 8; ++k) {
      const CellIndex n{c.x + kDx[k], c.y + kDy[k]};
      if (k >= 4) {
        // Diagonal: both orthogonal neighbours must be free (no squeezing past a corner).
        const bool x_ok = free_side[kDx[k] > 0 ? 0 : 1];
        const bool y_ok = free_side[kDy[k] > 0 ? 2 : 3];
        if (!x_ok || !y_ok) continue;
      }
      if (!g.contains(n)) continue;
      const auto ni = static_cast<std::int32_t>(g.index(n));
      if (blocked(static_cast<std::size_t>(ni))) continue;
      if (k < 4) free_side[k] = true;
      const float cost =
          g_[cur] + (k < 4 ? 1.0F : kSqrt2) * step_weight(static_cast<std::size_t>(ni));
      if (seen_[ni] != generation_) {
        seen_[ni] = generation_;
        g_[ni] = cost;
        f_[ni] = cost + octile(n, goal);
        parent_[ni] = static_cast<std::uint8_t>(k);
        heap_push(ni);
      } else if (heap_pos_[ni] >= 0 && cost < g_[ni]) {
        f_[ni] -= g_[ni] - cost;
        g_[ni] = cost;
        parent_[ni] = static_cast<std::uint8_t>(k);
        heap_decrease(ni);
      }
    }
  }
  return false;
}

bool Planner::line_of_sight(const Vec2& a, const Vec2& b, float& cost) const {
  const auto& g = geometry();
  // The traversal stays within the box of the two end cells, give or take one cell where
  // rounding lets it step past b's cell: with both end cells a cell inside the grid, every
  // visited cell is in the grid, and the hot loop needs no bounds check (it runs ~80 times per
  // replanning, along the whole path).
  const auto well_inside = [&](CellIndex c) {
    return c.x >= 1 && c.y >= 1 && c.x < g.cells_x() - 1 && c.y < g.cells_y() - 1;
  };
  int cells = 0;
  float weight = 0.0F;
  const auto visit = [&](std::size_t i) {  // counts the cell, then: is it blocked?
    ++cells;
    weight += step_weight(i);
    return blocked(i);
  };
  const bool hit =
      well_inside(g.cell_of(a)) && well_inside(g.cell_of(b))
          ? any_cell_on_segment(g, a, b, [&](CellIndex c) { return visit(g.index(c)); })
          : any_cell_on_segment(g, a, b,
                                [&](CellIndex c) { return !g.contains(c) || visit(g.index(c)); });
  // The segment's length in cells, each part weighted as the cells it crosses.
  const auto length = static_cast<float>((b - a).norm() / g.resolution());
  cost = cells > 0 ? length * weight / static_cast<float>(cells) : length;
  return !hit;
}

void Planner::smooth(const Vec2& start, const Vec2& goal, Path& out) {
  // Points to pull the string through: the start, the centres of the path cells, the goal.
  const auto point = [&](std::size_t i) {
    if (i == 0) return start;
    if (i == cells_.size() + 1) return goal;
    return geometry().center_of(cells_[i - 1]);
  };
  // The search's cost from the start to each point (the goal: its cell's).
  const auto cost_at = [&](std::size_t i) {
    if (i == 0) return 0.0F;
    return g_[geometry().index(cells_[std::min(i, cells_.size()) - 1])];
  };
  // A shortcut may cost what the grid path did between its ends, and a little more: the grid's
  // own zig-zag (octile steps) is no reason to keep one.
  constexpr float kSlack = 0.5F;
  const std::size_t n = cells_.size() + 2;
  out.waypoints.clear();
  (void)out.waypoints.push_back(start);
  std::size_t anchor = 0;
  while (anchor + 1 < n) {
    std::size_t next = anchor + 1;
    float cost = 0.0F;
    while (next + 1 < n && line_of_sight(point(anchor), point(next + 1), cost) &&
           (clearance_cost_ == 0.0F || cost <= cost_at(next + 1) - cost_at(anchor) + kSlack))
      ++next;
    if (!out.waypoints.push_back(point(next))) break;  // capacity: the plan ends early
    anchor = next;
  }
  out.length_m = 0.0;
  for (std::size_t i = 1; i < out.waypoints.size(); ++i) {
    out.length_m += (out.waypoints[i] - out.waypoints[i - 1]).norm();
  }
}

PlanResult Planner::plan(const MapStore& map, const Vec2& start, const Vec2& goal,
                         std::span<const DiscObstacle> others, Path& out) {
  map_ = &map;
  ++generation_;
  if (generation_ == 0) {  // wrapped: stale stamps could match again
    seen_.fill(0);
    overlay_.fill(0);
    generation_ = 1;
  }
  const auto& g = geometry();
  for (const DiscObstacle& d : others) {
    const int r = static_cast<int>(std::ceil(d.radius_m / g.resolution()));
    const CellIndex c = g.cell_of(d.center);
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        const CellIndex n{c.x + dx, c.y + dy};
        if (g.contains(n) && (g.center_of(n) - d.center).norm() <= d.radius_m) {
          overlay_[g.index(n)] = generation_;
        }
      }
    }
  }
  out.waypoints.clear();
  out.length_m = 0.0;
  CellIndex s = g.cell_of(start), t = g.cell_of(goal);
  if (!g.contains(s)) return PlanResult::kStartBlocked;
  if (!g.contains(t)) return PlanResult::kGoalBlocked;
  if (blocked(s) && !nearest_free(s, s)) return PlanResult::kStartBlocked;
  if (blocked(t) && !nearest_free(t, t)) return PlanResult::kGoalBlocked;
  if (!search(s, t)) return PlanResult::kNoPath;
  grid_cost_m_ = static_cast<double>(g_[g.index(t)]) * g.resolution();

  // Walk back from the goal, then keep the first kMaxPathPoints cells from the start.
  const auto back = [&](CellIndex c) {
    const std::uint8_t k = parent_[g.index(c)];
    return k == kNoParent ? c : CellIndex{c.x - kDx[k], c.y - kDy[k]};
  };
  std::size_t length = 1;
  for (CellIndex c = t; c != s && length <= limits::kGridCells2d; c = back(c))
    ++length;
  const std::size_t kept = std::min(length, cells_.capacity());
  (void)cells_.resize(kept);
  std::size_t pos = length;
  for (CellIndex c = t; pos > 0; c = back(c)) {
    if (--pos < kept) cells_[pos] = c;
  }
  // The robot's own position and the goal are the ends (they may lie in an escaped cell).
  const Vec2 end = kept == length ? goal : g.center_of(cells_.back());
  smooth(start, end, out);
  return PlanResult::kOk;
}

}  // namespace colag
