#include <gtest/gtest.h>

#include <cmath>

#include "colag/common/map_window.hpp"

using namespace colag;

namespace {

const GridGeometry2d kWindow{-20.0, -20.0, 0.1, 400, 400};

GridGeometry2d moved(const GridGeometry2d& g, const Vec2& origin) {
  return {origin.x(), origin.y(), g.resolution(), g.cells_x(), g.cells_y()};
}

bool on_lattice(const GridGeometry2d& g, const Vec2& origin) {
  int dx = 0, dy = 0;
  return window_step(g, origin, dx, dy).is_ok();
}

}  // namespace

TEST(MapWindow, StaysWhileItHoldsTheRobotAndItsGoal) {
  const WindowPolicy p;
  // The paper's layout: 4 m from the edge, the goal inside: no move.
  EXPECT_FALSE(window_move(kWindow, Vec2(12.0, 16.0), Vec2(12.0, -16.0), p));
  EXPECT_FALSE(window_move(kWindow, Vec2(0.0, 18.5), Vec2(0.0, -18.0), p));
  // Half a metre from the edge: it moves even with the goal inside.
  const auto o = window_move(kWindow, Vec2(0.0, 19.5), Vec2(0.0, -16.0), p);
  ASSERT_TRUE(o);
  const GridGeometry2d g = moved(kWindow, *o);
  EXPECT_GE(inset_in(g, Vec2(0.0, 19.5)), p.edge_m);
  EXPECT_LT(inset_in(g, Vec2(0.0, -16.0)), 0.0);  // 35.5 m away: ahead, out of the window
  // A goal that fits with both edge_m inside: both are.
  const auto both = window_move(kWindow, Vec2(0.0, 19.5), Vec2(3.0, 0.0), p);
  ASSERT_TRUE(both);
  EXPECT_GE(inset_in(moved(kWindow, *both), Vec2(3.0, 0.0)), p.edge_m);
  EXPECT_GE(inset_in(moved(kWindow, *both), Vec2(0.0, 19.5)), p.edge_m);
  EXPECT_TRUE(on_lattice(kWindow, *o));
  EXPECT_FALSE(window_move(kWindow, Vec2(0.0, 0.0), Vec2(1e9, 0.0), p));  // not near an edge yet
  // A robot standing off the lattice near the edge, its goal far: one move, then none (the
  // lattice's rounding once left it 7.99 m from the edge, and it "moved" every step).
  const GridGeometry2d here = moved(kWindow, Vec2(-14.0, 10.5));
  const auto once = window_move(here, Vec2(6.01, 50.5 - 7.99), Vec2(6.1, -42.7), p);
  ASSERT_TRUE(once);
  EXPECT_FALSE(window_move(moved(here, *once), Vec2(6.01, 50.5 - 7.99), Vec2(6.1, -42.7), p));
  EXPECT_FALSE(window_move(kWindow, Vec2(NAN, 0.0), Vec2(1.0, 0.0), p));
}

TEST(MapWindow, LeadsTowardsAFarGoalAndFollowsARobotAllTheWay) {
  const WindowPolicy p;
  GridGeometry2d g = kWindow;
  const Vec2 start(95.0, -100.0), goal(-40.0, 90.0);  // outside the first window, 233 m apart
  int moves = 0;
  double least_inset = 1e9;
  const Vec2 d = (goal - start).normalized();
  for (double s = 0.0; s <= (goal - start).norm(); s += 0.1) {
    const Vec2 at = start + s * d;
    if (const auto o = window_move(g, at, goal, p)) {
      ASSERT_TRUE(on_lattice(g, *o));
      g = moved(g, *o);
      ++moves;
      EXPECT_FALSE(window_move(g, at, goal, p)) << "moved twice at " << s;
    }
    // Well inside while the goal is beyond the window (the lattice rounds); once it holds the
    // goal, the robot drives to it wherever it is in the window.
    if (inset_in(g, goal) < 0.0) least_inset = std::min(least_inset, inset_in(g, at));
    EXPECT_GE(inset_in(g, at), p.hard_edge_m);
  }
  EXPECT_GE(least_inset, p.edge_m - 0.2);
  EXPECT_GE(inset_in(g, goal), 0.0);  // the goal's window at the end
  // Moves of ~(40 - 2 * 8) / 0.8 m along the diagonal: far from one per step.
  EXPECT_GE(moves, 5);
  EXPECT_LE(moves, 14);
}

TEST(MapWindow, WithoutADestinationMovesOnlyTheAxisThatNeedsIt) {
  const WindowPolicy p{.edge_m = 10.0, .hard_edge_m = 1.0};
  EXPECT_FALSE(window_move(kWindow, Vec2(18.5, 3.0), std::nullopt, p));
  const auto o = window_move(kWindow, Vec2(19.5, 3.0), std::nullopt, p);
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->x(), -20.0 + 9.5, 1e-9);  // the robot 10 m inside the east edge
  EXPECT_DOUBLE_EQ(o->y(), -20.0);
  // Outside the window altogether (a UAV taking off far away): inside by edge_m.
  const auto far = window_move(kWindow, Vec2(-100.0, 250.0), std::nullopt, p);
  ASSERT_TRUE(far);
  const GridGeometry2d g = moved(kWindow, *far);
  EXPECT_NEAR(inset_in(g, Vec2(-100.0, 250.0)), 10.0, 0.1);
}

TEST(MapWindow, ClipsTheWayToAFarGoalAtTheWindowsEdge) {
  const Vec2 from(0.0, 10.0);
  EXPECT_EQ(clip_into(kWindow, from, Vec2(5.0, -5.0), 1.0), Vec2(5.0, -5.0));
  const Vec2 c = clip_into(kWindow, from, Vec2(0.0, -100.0), 1.0);
  EXPECT_NEAR(c.x(), 0.0, 1e-9);
  EXPECT_NEAR(c.y(), -19.0, 1e-9);
  const Vec2 diag = clip_into(kWindow, from, Vec2(100.0, -90.0), 1.0);
  EXPECT_NEAR(inset_in(kWindow, diag), 1.0, 1e-9);
  EXPECT_NEAR((diag - from).normalized().dot(Vec2(1.0, -1.0).normalized()), 1.0, 1e-9);
  // From outside the margin: the goal clamped into the window.
  const Vec2 out = clip_into(kWindow, Vec2(0.0, 19.8), Vec2(50.0, 60.0), 1.0);
  EXPECT_NEAR(out.x(), 19.0, 1e-9);
  EXPECT_NEAR(out.y(), 19.0, 1e-9);
}

TEST(MapWindow, StepsOnlyOnTheLattice) {
  int dx = 0, dy = 0;
  ASSERT_TRUE(window_step(kWindow, Vec2(-19.0, -23.5), dx, dy).is_ok());
  EXPECT_EQ(dx, 10);
  EXPECT_EQ(dy, -35);
  EXPECT_FALSE(window_step(kWindow, Vec2(-19.03, 0.0), dx, dy).is_ok());
  EXPECT_FALSE(window_step(kWindow, Vec2(INFINITY, 0.0), dx, dy).is_ok());
  EXPECT_FALSE(window_step(kWindow, Vec2(2e6, 0.0), dx, dy).is_ok());
}
