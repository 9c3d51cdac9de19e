// UAV-UAV separation (beyond the paper): simulated UAV bodies flown by their flight planners,
// each keeping clear of the others through separate().
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "colag/common/map_store.hpp"
#include "colag/sim/world/uav_body.hpp"
#include "colag/uav/flight_planner.hpp"
#include "colag/uav/separation.hpp"

using namespace colag;
using namespace std::chrono_literals;

namespace {

struct Flyer {
  Flyer(const Vec2& from, const Vec2& to) : body({}, Vec3(from.x(), from.y(), 1.0)), goal(to) {}
  sim::UavBody body;
  uav::FlightPlanner planner{{}};
  Vec2 goal;
  bool cooperates = true;
  bool dead = false;
};

// Flies them for `seconds` at 50 Hz; the dead ones hover where they are. The closest pair, 2-D.
double fly(std::vector<Flyer>& flyers, double seconds) {
  MapStore empty;
  TimePoint t{};
  for (Flyer& f : flyers)
    f.planner.set_target(f.goal, t, f.body.state().pose.p.head<2>(), empty);
  double closest = 1e9;
  for (int k = 0; k < static_cast<int>(seconds / 0.02); ++k) {
    t += 20ms;
    for (std::size_t i = 0; i < flyers.size(); ++i) {
      Flyer& f = flyers[i];
      f.body.step(t, 0.02);
      hal::UavState s;
      while (f.body.poll(s)) {
      }
      if (f.dead) continue;
      uav::Neighbours others;
      for (std::size_t j = 0; j < flyers.size(); ++j) {
        if (j == i) continue;
        const hal::UavState& o = flyers[j].body.state();
        (void)others.push_back({o.pose.p.head<2>(), o.velocity_mps.head<2>(),
                                flyers[j].cooperates && !flyers[j].dead});
      }
      EXPECT_TRUE(f.body.send_setpoint(f.planner.step(f.body.state(), t, 0.02, empty, others)));
    }
    for (std::size_t i = 0; i < flyers.size(); ++i) {
      for (std::size_t j = i + 1; j < flyers.size(); ++j) {
        closest = std::min(closest, (flyers[i].body.state().pose.p.head<2>() -
                                     flyers[j].body.state().pose.p.head<2>())
                                        .norm());
      }
    }
  }
  return closest;
}

double to_goal(const Flyer& f) {
  return (f.body.state().pose.p.head<2>() - f.goal).norm();
}

}  // namespace

TEST(Separation, TwoUavsHeadOnBothTurnRightPassAndArrive) {
  std::vector<Flyer> f;
  f.emplace_back(Vec2(0, 0), Vec2(20, 0));
  f.emplace_back(Vec2(20, 0), Vec2(0, 0));
  const double closest = fly(f, 30.0);
  EXPECT_GT(closest, 1.3);  // 1.5 m asked; the acceleration limit may cut a little into it
  EXPECT_LT(to_goal(f[0]), 0.3);
  EXPECT_LT(to_goal(f[1]), 0.3);
}

TEST(Separation, FourUavsCrossingAtOnePointKeepApartAndArrive) {
  std::vector<Flyer> f;
  f.emplace_back(Vec2(-10, 0), Vec2(10, 0));
  f.emplace_back(Vec2(10, 0), Vec2(-10, 0));
  f.emplace_back(Vec2(0, -10), Vec2(0, 10));
  f.emplace_back(Vec2(0, 10), Vec2(0, -10));
  const double closest = fly(f, 40.0);
  EXPECT_GT(closest, 1.3);
  for (const Flyer& x : f)
    EXPECT_LT(to_goal(x), 0.3);
}

TEST(Separation, AUavThatDoesNotCooperateIsKeptClearOfAlone) {
  // A dead UAV hovering on the line: the live one goes around it, keeping the whole distance.
  std::vector<Flyer> f;
  f.emplace_back(Vec2(0, 0), Vec2(20, 0));
  f.emplace_back(Vec2(10, 0.1), Vec2(10, 0.1));
  f[1].dead = true;
  const double closest = fly(f, 30.0);
  EXPECT_GT(closest, 1.3);
  EXPECT_LT(to_goal(f[0]), 0.3);
}

TEST(Separation, AStopBehindADeadUavsStoppingLineIsReachedRoundIt) {
  // As in a 2-UAV field mission: the peer fell silent flying from (-5.0, 0.3) towards
  // (-4.3, -2.3); the live UAV's stop lies behind that line, its path straight through it. It
  // once stood at the line's edge for 80 s: the sideways step cancelled its slide round it.
  uav::Neighbours dead;
  (void)dead.push_back({Vec2(-5.02, 0.34), Vec2::Zero(), false, Vec2(-4.26, -2.25)});
  const Vec2 goal = uav::clear_of(Vec2(-6.8, -2.89), dead, 2.0);
  sim::UavBody body({}, Vec3(-1.5, 1.0, 1.0));
  auto planner = std::make_unique<uav::FlightPlanner>(uav::FlightPlannerConfig{});
  MapStore empty;
  TimePoint t{};
  planner->set_target(goal, t, body.state().pose.p.head<2>(), empty);
  double closest = 1e9;
  for (int k = 0; k < 1000; ++k) {  // 20 s
    t += 20ms;
    body.step(t, 0.02);
    hal::UavState s;
    while (body.poll(s)) {
    }
    const Vec2 p = body.state().pose.p.head<2>();
    closest = std::min(closest, (p - dead[0].nearest(p)).norm());
    ASSERT_TRUE(body.send_setpoint(planner->step(body.state(), t, 0.02, empty, dead)));
  }
  EXPECT_LT((body.state().pose.p.head<2>() - goal).norm(), 0.3);
  EXPECT_GT(closest, 1.3);
}

TEST(Separation, ADeadUavsKeepOutIsPlannedRound) {
  // Its stopping line lies across the way, 6 m long: the path goes round its end, clear of it by
  // the separation, instead of straight at it (leaving the filter to slide along it).
  uav::Neighbours dead;
  (void)dead.push_back({Vec2(5, -3), Vec2::Zero(), false, Vec2(5, 3)});
  // Planners hold their search grids: on the heap, not on the test's stack.
  auto planner = std::make_unique<uav::FlightPlanner>(uav::FlightPlannerConfig{});
  MapStore empty;
  planner->set_target(Vec2(10, 0), TimePoint{}, Vec2(0, 0), empty, dead);
  const Path& path = planner->path();
  ASSERT_GT(path.waypoints.size(), 2u);
  const double min_m = uav::SeparationConfig{}.min_m;
  for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
    for (double t = 0.0; t <= 1.0; t += 0.01) {
      const Vec2 q = path.waypoints[i - 1] + t * (path.waypoints[i] - path.waypoints[i - 1]);
      EXPECT_GT((q - dead[0].nearest(q)).norm(), min_m) << q.transpose();
    }
  }
  // A peer that flies the mission moves: it is not planned round.
  dead[0].cooperates = true;
  planner = std::make_unique<uav::FlightPlanner>(uav::FlightPlannerConfig{});
  planner->set_target(Vec2(10, 0), TimePoint{}, Vec2(0, 0), empty, dead);
  EXPECT_EQ(planner->path().waypoints.size(), 2u);
}

TEST(Separation, WithoutTheFilterTheyWouldMeet) {
  // The same head-on pair, neither told of the other: the test above measures something.
  std::vector<Flyer> f;
  f.emplace_back(Vec2(0, 0), Vec2(20, 0));
  f.emplace_back(Vec2(20, 0), Vec2(0, 0));
  MapStore empty;
  TimePoint t{};
  for (Flyer& x : f)
    x.planner.set_target(x.goal, t, x.body.state().pose.p.head<2>(), empty);
  double closest = 1e9;
  for (int k = 0; k < 1500; ++k) {
    t += 20ms;
    for (Flyer& x : f) {
      x.body.step(t, 0.02);
      ASSERT_TRUE(x.body.send_setpoint(x.planner.step(x.body.state(), t, 0.02, empty)));
    }
    closest = std::min(closest, (f[0].body.state().pose.p - f[1].body.state().pose.p).norm());
  }
  EXPECT_LT(closest, 0.5);
}

TEST(Separation, ASilentPeersWholeStoppingLineIsKeptClear) {
  // Last heard at the origin flying +x at 3 m/s: it may be anywhere up to p_end.
  uav::Neighbour dead{Vec2(0, 0), Vec2::Zero(), false, Vec2(7.5, 0)};
  EXPECT_NEAR((dead.nearest(Vec2(4, 3)) - Vec2(4, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((dead.nearest(Vec2(-2, 1)) - Vec2(0, 0)).norm(), 0.0, 1e-12);
  uav::Neighbours n;
  (void)n.push_back(dead);
  // A point to fly to inside its keep-out is moved to its edge, on the near side.
  const Vec2 q = uav::clear_of(Vec2(5, 0.5), n, 2.0);
  EXPECT_NEAR(q.x(), 5.0, 1e-9);
  EXPECT_NEAR(q.y(), 2.0, 1e-9);
  EXPECT_EQ(uav::clear_of(Vec2(5, 3), n, 2.0), Vec2(5, 3));  // outside: unchanged
  // A cooperating peer keeps its own half: a point is not moved for it.
  n[0].cooperates = true;
  EXPECT_EQ(uav::clear_of(Vec2(5, 0.5), n, 2.0), Vec2(5, 0.5));
  // Flying straight at the line: the approach is cut to what brakes to a stand at min_m, and
  // what it loses is turned to the right.
  uav::SeparationConfig c;
  n[0].cooperates = false;
  const Vec2 v = uav::separate(Vec2(4, -2.5), Vec2(0, 3), n, 3.0, c);
  EXPECT_NEAR(v.y(), std::min(std::sqrt(2.0 * c.brake_mps2 * 1.0), c.rate_per_s * 1.0), 1e-9);
  EXPECT_GT(v.x(), 0.0);  // towards +y, its right is +x
  EXPECT_LE(v.norm(), 3.0 + 1e-12);
}
