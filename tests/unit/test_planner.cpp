#include <gtest/gtest.h>

#include <memory>
#include <queue>
#include <vector>

#include "colag/common/grid_line.hpp"
#include "colag/common/planner.hpp"
#include "colag/common/random.hpp"
#include "colag/ugv/trajectory.hpp"
#include "map_fixtures.hpp"

using namespace colag;
using namespace colag::ugv;  // Trajectory

namespace {

class PlannerTest : public ::testing::Test {
 protected:
  std::unique_ptr<MapStore> map = std::make_unique<MapStore>();
  std::unique_ptr<Planner> planner = std::make_unique<Planner>();
  Path path;

  // An independent Dijkstra on the same 8-connected grid, same no-corner-cutting rule.
  double dijkstra_m(const Vec2& a, const Vec2& b) const {
    const auto& g = map->geometry();
    std::vector<double> dist(g.size(), 1e18);
    using Item = std::pair<double, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
    const std::size_t s = g.index(g.cell_of(a)), t = g.index(g.cell_of(b));
    dist[s] = 0;
    q.push({0, s});
    const auto free = [&](CellIndex c) { return g.contains(c) && !map->plan_blocked(c); };
    while (!q.empty()) {
      const auto [d, i] = q.top();
      q.pop();
      if (d > dist[i]) continue;
      if (i == t) return d * g.resolution();
      const CellIndex c = g.cell_at(i);
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const CellIndex n{c.x + dx, c.y + dy};
          if ((dx == 0 && dy == 0) || !free(n)) continue;
          if (dx != 0 && dy != 0 && (!free({c.x + dx, c.y}) || !free({c.x, c.y + dy}))) continue;
          const double nd = d + ((dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0);
          if (nd < dist[g.index(n)]) {
            dist[g.index(n)] = nd;
            q.push({nd, g.index(n)});
          }
        }
      }
    }
    return -1;
  }

  void expect_segments_free() const {
    for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
      const bool hit =
          any_cell_on_segment(map->geometry(), path.waypoints[i - 1], path.waypoints[i],
                              [&](CellIndex c) { return map->plan_blocked(c); });
      EXPECT_FALSE(hit) << "segment " << i << " crosses a blocked P-Map cell";
    }
  }
};

// A wall along y = 0 from x = -6 to x = 6 with a gap x in [2, 4].
CellState wall_with_gap(const Vec2& p) {
  const bool in_wall =
      std::abs(p.y()) < 0.1 && std::abs(p.x()) < 6.0 && !(p.x() > 2.0 && p.x() < 4.0);
  return in_wall ? CellState::kOccupied : CellState::kFree;
}

}  // namespace

TEST_F(PlannerTest, OpenSpaceGivesTheStraightLine) {
  ASSERT_EQ(planner->plan(*map, Vec2(0.03, -5.0), Vec2(3.0, 4.02), {}, path), PlanResult::kOk);
  ASSERT_EQ(path.waypoints.size(), 2u);
  EXPECT_NEAR(path.length_m, (Vec2(3.0, 4.02) - Vec2(0.03, -5.0)).norm(), 1e-9);
}

TEST_F(PlannerTest, FindsTheShortestRouteThroughAGap) {
  ASSERT_TRUE(test::fill_map(*map, -8, -5, 8, 5, wall_with_gap));
  const Vec2 start(0.05, -3.05), goal(0.05, 2.95);
  ASSERT_EQ(planner->plan(*map, start, goal, {}, path), PlanResult::kOk);
  // The grid path is optimal on the grid ...
  EXPECT_NEAR(planner->last_grid_cost_m(), dijkstra_m(start, goal), 1e-4);
  // ... and the any-angle path is no longer than it and close to the hand calculation: around
  // the gap's inner corner (x = 2, inflated by 0.4 m + one cell) on both sides of the wall.
  EXPECT_LE(path.length_m, planner->last_grid_cost_m() + 1e-9);
  const double cx = 2.0 + 0.4 + 0.1, cy = 0.1 + 0.4 + 0.1;
  const double hand = (Vec2(cx, -cy) - start).norm() + 2 * cy + (goal - Vec2(cx, cy)).norm();
  EXPECT_NEAR(path.length_m, hand, 0.05 * hand);
  expect_segments_free();
  for (const Vec2& w : path.waypoints)
    EXPECT_GT(w.x(), -0.5);  // it went through the gap
}

namespace {
// The closest any point of the path comes to an occupied cell (sampled every 2 cm), up to 1 m.
double path_clearance_m(const MapStore& map, const Path& path) {
  double closest = 1.0;
  for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
    const Vec2 a = path.waypoints[i - 1], b = path.waypoints[i];
    const int n = static_cast<int>((b - a).norm() / 0.02) + 1;
    for (int k = 0; k <= n; ++k)
      closest = std::min(closest, map.occupied_distance(a + (b - a) * (double(k) / n), 1.0));
  }
  return closest;
}
}  // namespace

TEST(PlannerClearance, KeepsClearOfACornerWhereTheDetourIsCheap) {
  // A 2 m box across the straight line: the plain path rounds its corner at the P-Map's 0.4 m;
  // with the clearance band (0.7 m, steps in it cost twice) the path keeps ~0.7 m, for a few
  // centimetres more length.
  const auto box = [](const Vec2& p) {
    return (p.cwiseAbs().maxCoeff() < 1.0) ? CellState::kOccupied : CellState::kFree;
  };
  const Vec2 start(-4.05, -0.55), goal(4.05, 0.45);
  Path plain, clear;
  const auto plain_map = std::make_unique<MapStore>();
  ASSERT_TRUE(test::fill_map(*plain_map, -6, -6, 6, 6, box));
  ASSERT_EQ(Planner().plan(*plain_map, start, goal, {}, plain), PlanResult::kOk);
  const auto band_map = std::make_unique<MapStore>(MapStoreConfig{.clearance_m = 0.7});
  ASSERT_TRUE(test::fill_map(*band_map, -6, -6, 6, 6, box));
  auto planner = std::make_unique<Planner>(PlannerConfig{.clearance_cost = 1.0});
  ASSERT_EQ(planner->plan(*band_map, start, goal, {}, clear), PlanResult::kOk);
  EXPECT_LT(path_clearance_m(*plain_map, plain), 0.55);
  EXPECT_GE(path_clearance_m(*band_map, clear), 0.65);
  EXPECT_LT(clear.length_m, plain.length_m + 0.5);
  // The band changes the cost, not what is blocked: the plain planner on the band's map plans
  // the plain path.
  Path again;
  ASSERT_EQ(Planner().plan(*band_map, start, goal, {}, again), PlanResult::kOk);
  EXPECT_NEAR(again.length_m, plain.length_m, 1e-9);
  // A robot sure of where it is uses none of the cost (the UGV scales it by its recent 3 sigma),
  // half of it keeps some of the room.
  planner->set_clearance_share(0.0);
  ASSERT_EQ(planner->plan(*band_map, start, goal, {}, again), PlanResult::kOk);
  EXPECT_NEAR(again.length_m, plain.length_m, 1e-9);
  planner->set_clearance_share(0.5);
  EXPECT_FLOAT_EQ(planner->clearance_cost(), 0.5F);
  ASSERT_EQ(planner->plan(*band_map, start, goal, {}, again), PlanResult::kOk);
  EXPECT_GT(path_clearance_m(*band_map, again), path_clearance_m(*plain_map, plain));
}

TEST(PlannerClearance, StillTakesAGapNarrowerThanTheBand) {
  // A wall from x = -6 to 6 with a 1.2 m gap at x in [2, 3.2]: the whole gap is in the band,
  // the way round the wall's end is ~8 m longer. The path still goes through the gap.
  const auto wall = [](const Vec2& p) {
    const bool in_wall =
        std::abs(p.y()) < 0.1 && std::abs(p.x()) < 6.0 && !(p.x() > 2.0 && p.x() < 3.2);
    return in_wall ? CellState::kOccupied : CellState::kFree;
  };
  const auto map = std::make_unique<MapStore>(MapStoreConfig{.clearance_m = 0.7});
  ASSERT_TRUE(test::fill_map(*map, -8, -5, 8, 5, wall));
  auto planner = std::make_unique<Planner>(PlannerConfig{.clearance_cost = 1.0});
  Path path;
  ASSERT_EQ(planner->plan(*map, Vec2(0.05, -3.05), Vec2(0.05, 2.95), {}, path), PlanResult::kOk);
  EXPECT_LT(path.length_m, 9.0);
  // Where the path crosses y = 0: in the gap (its free part, 0.4 m from each side).
  for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
    const Vec2 a = path.waypoints[i - 1], b = path.waypoints[i];
    if ((a.y() < 0.0) == (b.y() < 0.0)) continue;
    const double x = a.x() + (b.x() - a.x()) * (0.0 - a.y()) / (b.y() - a.y());
    EXPECT_GT(x, 2.35);
    EXPECT_LT(x, 2.85);
  }
}

TEST_F(PlannerTest, PlansWhereTheMapsWindowIsAfterItMoved) {
  // The window moved 60 m east: the same wall-with-gap scene there is planned through the gap,
  // as optimal as A* on the independent Dijkstra, and the old place is now outside.
  ASSERT_TRUE(map->move_to(Vec2(40.0, -20.0)));
  const Vec2 east(60.0, 0.0);
  ASSERT_TRUE(
      test::fill_map(*map, 52, -8, 68, 8, [&](const Vec2& p) { return wall_with_gap(p - east); }));
  const Vec2 a = east + Vec2(-3.0, -5.0), b = east + Vec2(0.0, 5.0);
  ASSERT_EQ(planner->plan(*map, a, b, {}, path), PlanResult::kOk);
  EXPECT_NEAR(planner->last_grid_cost_m(), dijkstra_m(a, b), 1e-3);
  expect_segments_free();
  bool through_gap = false;
  for (const Vec2& w : path.waypoints)
    through_gap = through_gap || (w.x() > east.x() + 1.5 && w.x() < east.x() + 4.5);
  EXPECT_TRUE(through_gap);
  EXPECT_EQ(planner->plan(*map, Vec2(0, -5), Vec2(0, 5), {}, path), PlanResult::kStartBlocked);
}

TEST_F(PlannerTest, ReportsNoPathWhenTheGoalIsWalledIn) {
  ASSERT_TRUE(test::fill_map(*map, -5, -5, 5, 5, [](const Vec2& p) {
    const double r = (p - Vec2(2, 2)).norm();
    return r > 1.0 && r < 1.3 ? CellState::kOccupied : CellState::kFree;
  }));
  EXPECT_EQ(planner->plan(*map, Vec2(-3, -3), Vec2(2, 2), {}, path), PlanResult::kNoPath);
  EXPECT_TRUE(path.waypoints.empty());
  EXPECT_EQ(planner->plan(*map, Vec2(-30, 0), Vec2(2, 2), {}, path), PlanResult::kStartBlocked);
  EXPECT_EQ(planner->plan(*map, Vec2(-3, -3), Vec2(1e9, 0), {}, path), PlanResult::kGoalBlocked);
}

TEST_F(PlannerTest, EscapesFromAnInflatedStartAndPlansAroundAnotherRobot) {
  ASSERT_TRUE(test::fill_map(*map, -5, -5, 5, 5, [](const Vec2& p) {
    return (p - Vec2(0.05, -1.95)).norm() < 0.06 ? CellState::kOccupied : CellState::kFree;
  }));
  // Start 0.3 m from an obstacle (inside its 0.4 m inflation): the plan still starts there.
  const Vec2 start(0.05, -1.65);
  ASSERT_TRUE(map->plan_blocked(start));
  const DiscObstacle other{Vec2(0.0, 1.0), 0.9};
  ASSERT_EQ(planner->plan(*map, start, Vec2(0.0, 3.0), {&other, 1}, path), PlanResult::kOk);
  EXPECT_EQ(path.waypoints.front(), start);
  // The straight line would pass through the other robot's disc; the plan keeps out of it.
  for (double s = 0; s <= 1.0; s += 0.01) {
    for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
      const Vec2 p = path.waypoints[i - 1] + s * (path.waypoints[i] - path.waypoints[i - 1]);
      EXPECT_GT((p - other.center).norm(), other.radius_m - 0.1);
    }
  }
}

TEST_F(PlannerTest, AnotherRobotsDiscDoesNotComeBackWhenTheStampsWrap) {
  // The per-cell stamps are 16 bits: 65 536 plans after a disc was stamped, its stamp is the
  // search's again. The wrap clears them, so the disc of the first plan does not block the one
  // 65 536 plans later (were they not cleared, it would: the straight line ran through it).
  const DiscObstacle other{Vec2(0.0, 0.0), 1.0};
  const Vec2 a(0.0, -3.0), b(0.0, 3.0);
  ASSERT_EQ(planner->plan(*map, a, b, {&other, 1}, path), PlanResult::kOk);
  ASSERT_GT(path.waypoints.size(), 2u);  // round the disc
  for (int i = 1; i < 65'535; ++i)
    ASSERT_EQ(planner->plan(*map, a, a, {}, path), PlanResult::kOk);  // start == goal: cheap
  ASSERT_EQ(planner->plan(*map, a, b, {}, path), PlanResult::kOk);
  EXPECT_EQ(path.waypoints.size(), 2u);
  EXPECT_NEAR(path.length_m, 6.0, 1e-9);
}

TEST_F(PlannerTest, TrajectoryRespectsSpeedAccelerationAndTurnRateLimits) {
  ASSERT_TRUE(test::fill_map(*map, -8, -5, 8, 5, wall_with_gap));
  ASSERT_EQ(planner->plan(*map, Vec2(-3, -3), Vec2(-2, 3), {}, path), PlanResult::kOk);
  ASSERT_GE(path.waypoints.size(), 3u);  // it has corners
  TrajectoryLimits lim;
  Trajectory traj;
  ASSERT_TRUE(traj.build(path, 0.0, lim));
  EXPECT_EQ(traj[0].v_mps, 0.0);
  EXPECT_EQ(traj.back().v_mps, 0.0);
  EXPECT_NEAR((traj.back().p - path.waypoints.back()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(traj.back().s_m, path.length_m, 0.3);  // rounded corners are a little shorter
  for (std::size_t i = 0; i < traj.size(); ++i) {
    const auto& s = traj[i];
    EXPECT_LE(s.v_mps, lim.v_max_mps + 1e-12);
    EXPECT_LE(std::abs(s.omega_radps), lim.omega_max_radps + 1e-9);
    if (i == 0) continue;
    const auto& a = traj[i - 1];
    const double ds = s.s_m - a.s_m;
    EXPECT_GT(s.t_s, a.t_s);
    EXPECT_LE(std::abs(s.v_mps * s.v_mps - a.v_mps * a.v_mps) / (2 * ds), lim.a_max_mps2 + 1e-9);
    EXPECT_LE((s.p - a.p).norm(), lim.spacing_m + 1e-9);
  }
  // Corner rounding stays within corner_deviation_m of the polyline.
  for (std::size_t i = 0; i < traj.size(); ++i) {
    double d = 1e9;
    for (std::size_t k = 1; k < path.waypoints.size(); ++k) {
      const Vec2 a = path.waypoints[k - 1], b = path.waypoints[k];
      const double t = std::clamp((traj[i].p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      d = std::min(d, (a + t * (b - a) - traj[i].p).norm());
    }
    EXPECT_LE(d, lim.corner_deviation_m + 1e-9);
  }
}

TEST(Trajectory, StartsAtTheCurrentSpeedAndTurnsOnTheSpotAtAReversal) {
  Path path;
  ASSERT_TRUE(path.waypoints.push_back(Vec2(0, 0)));
  ASSERT_TRUE(path.waypoints.push_back(Vec2(2, 0)));
  ASSERT_TRUE(path.waypoints.push_back(Vec2(0, 0.001)));  // back the way it came
  Trajectory traj;
  ASSERT_TRUE(traj.build(path, 0.4, {}));
  EXPECT_NEAR(traj[0].v_mps, 0.4, 1e-12);
  bool stopped_at_corner = false;
  for (std::size_t i = 0; i < traj.size(); ++i) {
    if ((traj[i].p - Vec2(2, 0)).norm() < 1e-6) stopped_at_corner = traj[i].v_mps == 0.0;
  }
  EXPECT_TRUE(stopped_at_corner);
}

// Planner::line_of_sight skips the bounds check when both end cells are a cell inside the grid,
// relying on this: the traversal never visits a cell more than one cell outside the box of the
// two end cells. Random segments, many ending exactly on cell boundaries and corners (where
// rounding may step past b's cell), all over the grid.
TEST(GridLine, StaysWithinACellOfTheBoxOfItsEndCells) {
  const GridGeometry2d& g = kWorldGrid2d;
  Rng rng(11);
  const auto random_point = [&] {
    Vec2 p(rng.uniform(-19.5, 19.5), rng.uniform(-19.5, 19.5));
    if (rng.uniform() < 0.5) p.x() = g.origin_x() + 0.1 * std::round((p.x() - g.origin_x()) / 0.1);
    if (rng.uniform() < 0.5) p.y() = g.origin_y() + 0.1 * std::round((p.y() - g.origin_y()) / 0.1);
    return p;
  };
  int worst = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec2 a = random_point();
    const Vec2 b = rng.uniform() < 0.2 ? a + 0.1 * Vec2(static_cast<double>(rng.below(5)),
                                                        static_cast<double>(rng.below(5)))
                                       : random_point();
    const CellIndex ca = g.cell_of(a), cb = g.cell_of(b);
    (void)any_cell_on_segment(g, a, b, [&](CellIndex c) {
      const int out_x = std::max({0, std::min(ca.x, cb.x) - c.x, c.x - std::max(ca.x, cb.x)});
      const int out_y = std::max({0, std::min(ca.y, cb.y) - c.y, c.y - std::max(ca.y, cb.y)});
      worst = std::max({worst, out_x, out_y});
      return false;
    });
  }
  RecordProperty("worst_cells_outside", worst);
  EXPECT_LE(worst, 1);
}
