#pragma once
// The UGV's copy of the map (paper Sec. III-B/C): a 2-D grid of free / occupied / unknown cells
// filled by the UAV's map patches, and two views kept up to date incrementally:
// - P-Map  (planning): occupied cells inflated by plan_inflation_m; unknown counts as free.
// - CP-Map (collision prediction): occupied and unknown cells inflated by
//   predict_inflation_m; everything is unknown (blocked) until patches arrive.
// - the clearance band (optional): cells within clearance_m of an occupied cell, where the
//   planner's steps cost more (Planner: clearance_cost), so that a path keeps room for the
//   robot's position uncertainty where the site leaves it.
// Inflation is exact in the safe direction: a cell is blocked when any point of it is within
// the radius of any point of a source cell (square-to-square distance), so "not blocked" means
// "more than the radius from every obstacle cell".
#include <array>
#include <cstdint>
#include <span>

#include "colag/common/grid2d.hpp"
#include "colag/common/map_patch_codec.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/status.hpp"
#include "colag/msg/map_patch.hpp"

namespace colag {

struct MapStoreConfig {
  double plan_inflation_m = 0.4;      // robot radius + clearance kept by the planner
  double predict_inflation_m = 0.25;  // robot radius: a 3-sigma ellipse touching means contact
  // Unknown cells block the CP-Map (a blind robot). False for a robot that sees for itself
  // (the self-perception baseline): only occupied cells block.
  bool unknown_blocks_prediction = true;
  // The clearance band's radius (0: none; at most kMaxInflationCells cells).
  double clearance_m = 0.0;
};

struct MapStoreCounters {
  std::uint64_t patches_applied = 0;
  std::uint64_t patches_rejected = 0;
  std::uint64_t cells_changed = 0;
  std::uint64_t plan_cells_blocked = 0;  // P-Map cells that became blocked (replanning trigger)
};

class MapStore {
 public:
  // 0.7 m at 0.1 m: the disc tables' capacity. The per-cell counts are 8 bits: the largest disc
  // holds 213 cells (disc_cells), so no count reaches 256.
  static constexpr int kMaxInflationCells = 7;
  // Cells of the disc that inflates one cell by radius_m (clamped to kMaxInflationCells).
  static int disc_cells(double radius_m);

  explicit MapStore(const MapStoreConfig& config = {});

  // Validates the whole patch (geometry, payload) before touching the map: a bad patch is
  // rejected and counted, never half-applied. A patch reaching past the window's edge is applied
  // where the window holds it; one wholly outside is refused. Several UAVs (patch.uav_id): a
  // patch's unknown cell does not erase a cell another UAV's patch made known (one UAV's map
  // may not hold yet what another's shows); a UAV may take back its own word.
  Status apply(const msg::MapPatch& patch);

  // The window of the site this map holds: limits' size, at kWorldGrid2d's place until moved.
  const GridGeometry2d& geometry() const { return geometry_; }
  // Moves the window so that its corner (cell (0, 0)'s) is at `origin` (on the grid's lattice:
  // a whole number of cells from where it is): the cells it keeps keep their state, the cells
  // that enter it are unknown, and both views are recomputed (a few ms: for a robot that drives
  // off its window's edge, not for every step). Refused (map unchanged) off the lattice or not
  // finite.
  Status move_to(const Vec2& origin);
  // Every cell's state, row-major over geometry() (a copy for telemetry is one memcpy).
  std::span<const CellState> cells() const { return state_; }
  // Outside the grid: unknown, and blocked in both views.
  CellState state(CellIndex c) const;
  bool plan_blocked(CellIndex c) const;
  bool predict_blocked(CellIndex c) const;
  // By row-major index of an in-grid cell (the planner's inner loop).
  bool plan_blocked_at(std::size_t i) const { return plan_count_[i] > 0; }
  bool predict_blocked_at(std::size_t i) const {
    return near_occupied_[i] > 0 || near_unknown_[i] > 0;
  }
  // The two reasons a CP-Map cell is blocked: an occupied or an unknown cell within the radius.
  bool near_occupied_at(std::size_t i) const { return near_occupied_[i] > 0; }
  bool near_unknown_at(std::size_t i) const { return near_unknown_[i] > 0; }
  // Within clearance_m of an occupied cell (always false with clearance_m 0).
  bool in_clearance_band_at(std::size_t i) const { return near_clear_[i] > 0; }
  // Distance from p to the nearest occupied cell's square, searching up to max_m (returned if
  // none is closer).
  double occupied_distance(const Vec2& p, double max_m) const;
  bool plan_blocked(const Vec2& p) const { return plan_blocked(geometry().cell_of(p)); }
  bool predict_blocked(const Vec2& p) const { return predict_blocked(geometry().cell_of(p)); }

  // The ground under the robot itself: the UAV cannot see under it, and its standing there is
  // proof that nothing else does. The unknown cells the disc covers (in part) become free;
  // returns how many did. Called after every patch, which may say unknown there again.
  int free_under(const Vec2& centre, double radius_m);

  const MapStoreConfig& config() const { return config_; }
  const MapStoreCounters& counters() const { return counters_; }

 private:
  // A disc of cells as one span of columns per row (dx0..dx1 at dy), so that stamping it adds
  // along contiguous memory.
  struct DiscRow {
    int dy, dx0, dx1;
  };
  struct Disc {
    StaticVector<DiscRow, 2 * kMaxInflationCells + 3> rows;
    int cells = 0;
    int reach = 0;  // largest |dx| or |dy|
  };
  using Counts = std::array<std::uint8_t, limits::kGridCells2d>;
  static void make_disc(double radius_m, Disc& out);
  // Calls f(first cell's index, cells) for each row span of `disc` centred on c, clipped to
  // the grid.
  template <class F>
  void each_span(CellIndex c, const Disc& disc, F&& f) const;
  void stamp(CellIndex c, const Disc& disc, Counts& counts, int delta);
  void set_cell(CellIndex c, CellState s);
  // Both views from scratch: as if every cell had been set one by one from unknown.
  void recount();

  GridGeometry2d geometry_ = kWorldGrid2d;
  MapStoreConfig config_;
  MapStoreCounters counters_;
  std::array<CellState, limits::kGridCells2d> state_;
  std::array<std::uint8_t, limits::kGridCells2d> source_;  // the UAV whose patch set each cell
  Counts plan_count_;                                      // occupied cells within plan_inflation_m
  Counts near_occupied_;  // occupied cells within predict_inflation_m
  Counts near_unknown_;   // unknown cells within predict_inflation_m (if they block prediction)
  Counts near_clear_;     // occupied cells within clearance_m
  Disc plan_disc_;
  Disc predict_disc_;
  Disc clear_disc_;  // empty (no rows) with clearance_m 0: stamping it touches nothing
  PatchCells scratch_;
};

}  // namespace colag
