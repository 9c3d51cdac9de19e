#pragma once
// Global path planner on the P-Map: A* over the 8-connected grid (no corner cutting, octile
// heuristic), then line-of-sight shortcutting ("string pulling") into an any-angle polyline
// whose segments cross only free P-Map cells. Static memory: per-cell arrays sized from the
// limits header, reset between searches by a generation counter instead of clearing.
// Other UGVs enter as discs blocked for this search only.
// Clearance: a step into the map's clearance band (MapStore::in_clearance_band_at) costs
// (1 + clearance_cost) times its length, so the path keeps away from obstacles where a detour
// is cheap, and the string is pulled only where that does not cost more than the grid path did
// (a plain shortcut would hug the corners again).
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "colag/common/limits.hpp"
#include "colag/common/map_store.hpp"
#include "colag/common/static_vector.hpp"

namespace colag {

struct DiscObstacle {
  Vec2 center = Vec2::Zero();
  double radius_m = 0.0;
};

struct PlannerConfig {
  std::size_t max_expansions = limits::kGridCells2d;
  double escape_radius_m = 1.0;  // how far the start/goal may be moved out of blocked cells
  double clearance_cost = 0.0;   // extra cost per cell length inside the clearance band
};

enum class PlanResult : std::uint8_t { kOk, kNoPath, kStartBlocked, kGoalBlocked };
const char* to_string(PlanResult r);

struct Path {
  StaticVector<Vec2, limits::kMaxWaypoints> waypoints;  // starts at the start, ends at the goal
  double length_m = 0.0;
};

class Planner {
 public:
  explicit Planner(const PlannerConfig& config = {}) : config_(config) { set_clearance_share(1.0); }

  PlanResult plan(const MapStore& map, const Vec2& start, const Vec2& goal,
                  std::span<const DiscObstacle> others, Path& out);

  // The share of config().clearance_cost the next plans use (clamped to [0, 1]): a robot sure
  // of where it is needs less room.
  void set_clearance_share(double share) {
    clearance_cost_ =
        static_cast<float>(std::max(config_.clearance_cost, 0.0) * std::clamp(share, 0.0, 1.0));
  }
  float clearance_cost() const { return clearance_cost_; }

  std::size_t last_expansions() const { return expansions_; }
  // Length of the last A* grid path (before shortcutting), metres.
  double last_grid_cost_m() const { return grid_cost_m_; }

 private:
  bool blocked(std::size_t i) const {
    return map_->plan_blocked_at(i) || overlay_[i] == generation_;
  }
  bool blocked(CellIndex c) const {
    return !geometry().contains(c) || blocked(geometry().index(c));
  }
  const GridGeometry2d& geometry() const { return map_->geometry(); }  // during plan()
  bool nearest_free(CellIndex from, CellIndex& out) const;
  bool search(CellIndex start, CellIndex goal);
  // True when the segment crosses no blocked cell; `cost` is its length in cells weighted as
  // the search weighs its steps.
  bool line_of_sight(const Vec2& a, const Vec2& b, float& cost) const;
  float step_weight(std::size_t i) const {
    return map_->in_clearance_band_at(i) ? 1.0F + clearance_cost_ : 1.0F;
  }
  void smooth(const Vec2& start, const Vec2& goal, Path& out);

  // Indexed binary heap on f (ties: smaller h first).
  void heap_push(std::int32_t cell);
  void heap_decrease(std::int32_t cell);
  std::int32_t heap_pop();
  void sift_up(std::int32_t pos);
  void sift_down(std::int32_t pos);
  bool before(std::int32_t a, std::int32_t b) const {
    return f_[a] < f_[b] || (f_[a] == f_[b] && f_[a] - g_[a] < f_[b] - g_[b]);
  }

  // The neighbour from which each cell was reached, as a step: kDx[k], kDy[k] back to it.
  static constexpr std::uint8_t kNoParent = 0xFF;
  static constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  static constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

  PlannerConfig config_;
  float clearance_cost_ = 0.0F;
  const MapStore* map_ = nullptr;
  // Per-cell stamps: 16 bits is enough (a wrap clears them: once in 65 535 plans).
  std::uint16_t generation_ = 0;
  std::size_t expansions_ = 0;
  double grid_cost_m_ = 0.0;
  std::array<std::uint16_t, limits::kGridCells2d> seen_{};     // == generation_: g_/f_ valid
  std::array<std::uint16_t, limits::kGridCells2d> overlay_{};  // == generation_: other UGV
  std::array<float, limits::kGridCells2d> g_{};
  std::array<float, limits::kGridCells2d> f_{};
  std::array<std::uint8_t, limits::kGridCells2d> parent_{};    // step k into it, or kNoParent
  std::array<std::int32_t, limits::kGridCells2d> heap_pos_{};  // -1: closed
  std::array<std::int32_t, limits::kGridCells2d> heap_{};
  std::int32_t heap_size_ = 0;
  StaticVector<CellIndex, limits::kMaxPathPoints> cells_;  // raw A* path, start first
};

}  // namespace colag
