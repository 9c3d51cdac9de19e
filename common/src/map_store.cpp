#include "colag/common/map_store.hpp"

#include <algorithm>
#include <cmath>

#include "colag/common/grid_shift.hpp"
#include "colag/common/map_window.hpp"

namespace colag {

template <class F>
void MapStore::each_span(CellIndex c, const Disc& disc, F&& f) const {
  const auto& g = geometry();
  for (const DiscRow& r : disc.rows) {
    const int y = c.y + r.dy;
    if (y < 0 || y >= g.cells_y()) continue;
    const int x0 = std::max(c.x + r.dx0, 0), x1 = std::min(c.x + r.dx1, g.cells_x() - 1);
    if (x0 <= x1) f(g.index(CellIndex{x0, y}), x1 - x0 + 1);
  }
}

MapStore::MapStore(const MapStoreConfig& config) : config_(config) {
  make_disc(config_.plan_inflation_m, plan_disc_);
  make_disc(config_.predict_inflation_m, predict_disc_);
  if (config_.clearance_m > 0.0) make_disc(config_.clearance_m, clear_disc_);
  state_.fill(CellState::kUnknown);
  source_.fill(0);
  recount();
}

void MapStore::recount() {
  plan_count_.fill(0);
  near_occupied_.fill(0);
  near_unknown_.fill(0);
  near_clear_.fill(0);
  const auto& g = geometry();
  if (config_.unknown_blocks_prediction) {
    // Every cell unknown first, so a cell's count is the number of disc cells inside the grid:
    // the whole disc away from the edges (stamping all 160 000 cells took ~10 ms per robot).
    const int reach = predict_disc_.reach;
    near_unknown_.fill(static_cast<std::uint8_t>(predict_disc_.cells));
    for (int y = 0; y < g.cells_y(); ++y) {
      const bool edge_row = y < reach || y >= g.cells_y() - reach;
      for (int x = 0; x < g.cells_x(); ++x) {
        if (!edge_row && x >= reach && x < g.cells_x() - reach) continue;
        int inside = 0;
        each_span({x, y}, predict_disc_, [&](std::size_t, int cells) { inside += cells; });
        near_unknown_[g.index(CellIndex{x, y})] = static_cast<std::uint8_t>(inside);
      }
    }
  }
  // Then what is known: each cell that is not unknown, as set_cell would have counted it (but
  // not as newly blocked: nothing changed where the robot is).
  const std::uint64_t blocked_before = counters_.plan_cells_blocked;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (state_[i] == CellState::kUnknown) continue;
    const CellIndex c = g.cell_at(i);
    if (config_.unknown_blocks_prediction) stamp(c, predict_disc_, near_unknown_, -1);
    if (state_[i] != CellState::kOccupied) continue;
    stamp(c, plan_disc_, plan_count_, +1);
    stamp(c, predict_disc_, near_occupied_, +1);
    stamp(c, clear_disc_, near_clear_, +1);
  }
  counters_.plan_cells_blocked = blocked_before;
}

Status MapStore::move_to(const Vec2& origin) {
  const GridGeometry2d& g = geometry_;
  int dx = 0, dy = 0;
  if (Status s = window_step(g, origin, dx, dy); !s.is_ok()) return s;
  if (dx == 0 && dy == 0) return Status::ok();
  const int nx = g.cells_x(), ny = g.cells_y();
  shift_layer(state_.data(), nx, ny, dx, dy, CellState::kUnknown);
  shift_layer(source_.data(), nx, ny, dx, dy, std::uint8_t{0});
  // On the lattice exactly (the caller's origin may be a rounding away from it).
  geometry_ = GridGeometry2d(g.origin_x() + dx * g.resolution(), g.origin_y() + dy * g.resolution(),
                             g.resolution(), nx, ny);
  recount();
  return Status::ok();
}

void MapStore::make_disc(double radius_m, Disc& out) {
  const double r_cells = std::clamp(radius_m, 0.0, kMaxInflationCells * limits::kGridResolution_m) /
                         limits::kGridResolution_m;
  const int n = static_cast<int>(std::ceil(r_cells)) + 1;
  out = Disc{};
  for (int dy = -n; dy <= n; ++dy) {
    // The cells whose square is within the radius of the centre cell's square (gap between the
    // two squares, in cells): a run of columns symmetric about dx = 0.
    const double gy = std::max(0, std::abs(dy) - 1);
    int half = -1;
    for (int dx = 0; dx <= n; ++dx) {
      const double gx = std::max(0, dx - 1);
      if (gx * gx + gy * gy <= r_cells * r_cells + 1e-9) half = dx;
    }
    if (half < 0) continue;
    (void)out.rows.push_back({dy, -half, half});
    out.cells += 2 * half + 1;
    out.reach = std::max({out.reach, std::abs(dy), half});
  }
}

int MapStore::disc_cells(double radius_m) {
  Disc d;
  make_disc(radius_m, d);
  return d.cells;
}

void MapStore::stamp(CellIndex c, const Disc& disc, Counts& counts, int delta) {
  int newly = 0;  // counts that became 1
  each_span(c, disc, [&](std::size_t first, int cells) {
    std::uint8_t* row = &counts[first];
    for (int i = 0; i < cells; ++i) {
      row[i] = static_cast<std::uint8_t>(row[i] + delta);
      newly += row[i] == 1 ? 1 : 0;
    }
  });
  if (&counts == &plan_count_ && delta > 0)
    counters_.plan_cells_blocked += static_cast<std::uint64_t>(newly);
}

void MapStore::set_cell(CellIndex c, CellState s) {
  const std::size_t i = geometry().index(c);
  const CellState old = state_[i];
  if (old == s) return;
  ++counters_.cells_changed;
  if (old == CellState::kOccupied) stamp(c, plan_disc_, plan_count_, -1);
  if (s == CellState::kOccupied) stamp(c, plan_disc_, plan_count_, +1);
  if (old == CellState::kOccupied) stamp(c, predict_disc_, near_occupied_, -1);
  if (s == CellState::kOccupied) stamp(c, predict_disc_, near_occupied_, +1);
  if (old == CellState::kOccupied) stamp(c, clear_disc_, near_clear_, -1);
  if (s == CellState::kOccupied) stamp(c, clear_disc_, near_clear_, +1);
  if (config_.unknown_blocks_prediction) {
    if (old == CellState::kUnknown) stamp(c, predict_disc_, near_unknown_, -1);
    if (s == CellState::kUnknown) stamp(c, predict_disc_, near_unknown_, +1);
  }
  state_[i] = s;
}

int MapStore::free_under(const Vec2& centre, double radius_m) {
  if (!all_finite(centre) || !(radius_m >= 0.0) || radius_m > 10.0) return 0;
  const auto& g = geometry();
  const CellIndex lo = g.cell_of(centre - Vec2::Constant(radius_m));
  const CellIndex hi = g.cell_of(centre + Vec2::Constant(radius_m));
  int freed = 0;
  for (int y = std::max(lo.y, 0); y <= std::min(hi.y, g.cells_y() - 1); ++y) {
    for (int x = std::max(lo.x, 0); x <= std::min(hi.x, g.cells_x() - 1); ++x) {
      // The cell's point nearest to the centre: a cell the robot stands on in part counts.
      const Vec2 d =
          ((g.center_of({x, y}) - centre).cwiseAbs() - Vec2::Constant(0.5 * g.resolution()))
              .cwiseMax(0.0);
      if (d.squaredNorm() > radius_m * radius_m || state_[g.index({x, y})] != CellState::kUnknown)
        continue;
      set_cell({x, y}, CellState::kFree);
      ++freed;
    }
  }
  return freed;
}

Status MapStore::apply(const msg::MapPatch& patch) {
  const auto reject = [&](Status s) {
    ++counters_.patches_rejected;
    return s;
  };
  const auto& g = geometry();
  if (!std::isfinite(patch.resolution_m) || std::abs(patch.resolution_m - g.resolution()) > 1e-9) {
    return reject({Errc::kInvalidArgument, "map patch: wrong resolution"});
  }
  if (!std::isfinite(patch.origin_x_m) || !std::isfinite(patch.origin_y_m)) {
    return reject({Errc::kInvalidArgument, "map patch: origin not finite"});
  }
  const double fx = (patch.origin_x_m - g.origin_x()) / g.resolution();
  const double fy = (patch.origin_y_m - g.origin_y()) / g.resolution();
  if (std::abs(fx - std::round(fx)) > 1e-6 || std::abs(fy - std::round(fy)) > 1e-6) {
    return reject({Errc::kInvalidArgument, "map patch: origin not on the grid"});
  }
  if (std::abs(fx) > 1e6 || std::abs(fy) > 1e6) {
    return reject({Errc::kOutOfRange, "map patch: outside the map"});
  }
  const CellIndex o{static_cast<int>(std::lround(fx)), static_cast<int>(std::lround(fy))};
  // The part inside the window is applied (a window that moves with its robot holds part of
  // a patch at its edge); a patch with no cell inside it is refused.
  const int x0 = std::max(o.x, 0), y0 = std::max(o.y, 0);
  const int x1 = std::min(o.x + static_cast<int>(patch.width_cells), g.cells_x());
  const int y1 = std::min(o.y + static_cast<int>(patch.height_cells), g.cells_y());
  if (x0 >= x1 || y0 >= y1) return reject({Errc::kOutOfRange, "map patch: outside the map"});
  if (Status s = decode_patch(patch, scratch_); !s) return reject(s);

  const auto source = static_cast<std::uint8_t>(std::min<unsigned>(patch.uav_id, 0xFF));
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const CellState s = scratch_.at(x - o.x, y - o.y);
      const std::size_t i = g.index(CellIndex{x, y});
      if (s == CellState::kUnknown && state_[i] != CellState::kUnknown && source_[i] != source)
        continue;  // another UAV knows it
      set_cell({x, y}, s);
      source_[i] = source;
    }
  }
  ++counters_.patches_applied;
  return Status::ok();
}

CellState MapStore::state(CellIndex c) const {
  return geometry().contains(c) ? state_[geometry().index(c)] : CellState::kUnknown;
}
bool MapStore::plan_blocked(CellIndex c) const {
  return !geometry().contains(c) || plan_count_[geometry().index(c)] > 0;
}
double MapStore::occupied_distance(const Vec2& p, double max_m) const {
  const auto& g = geometry();
  const CellIndex c = g.cell_of(p);
  const int r = static_cast<int>(std::ceil(max_m / g.resolution())) + 1;
  double best = max_m;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const CellIndex n{c.x + dx, c.y + dy};
      if (!g.contains(n) || state_[g.index(n)] != CellState::kOccupied) continue;
      // Distance from p to the cell's square.
      const Vec2 lo = g.center_of(n) - Vec2::Constant(0.5 * g.resolution());
      const Vec2 d = (lo - p).cwiseMax(p - (lo + Vec2::Constant(g.resolution()))).cwiseMax(0.0);
      best = std::min(best, d.norm());
    }
  }
  return best;
}

bool MapStore::predict_blocked(CellIndex c) const {
  return !geometry().contains(c) || predict_blocked_at(geometry().index(c));
}

}  // namespace colag
