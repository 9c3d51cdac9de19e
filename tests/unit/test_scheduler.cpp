#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <vector>

#include "colag/common/random.hpp"
#include "colag/uav/scheduler.hpp"
#include "colag/uav/time_cost.hpp"

using namespace colag;
using namespace colag::uav;

namespace {

// A support-scheduling instance like the UAV's: stops in the 27 m arena, first leg from a
// moving UAV, cruise legs d / v_max, open route, deadlines drawn from [lo, hi] seconds.
ScheduleProblem random_instance(Rng& rng, int n, double lo, double hi) {
  ScheduleProblem p;
  p.n = n;
  const FlightLimits lim;
  std::vector<Vec2> pts(static_cast<std::size_t>(n) + 1);
  for (auto& q : pts)
    q = Vec2(rng.uniform(-13.5, 13.5), rng.uniform(-13.5, 13.5));
  const Vec2 v(rng.uniform(-3, 3), rng.uniform(-3, 3));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      p.travel[i][j] = j == 0 ? 0.0
                              : (i == 0 ? first_leg_time_s(pts[0], v, pts[j], lim)
                                        : cruise_time_s(pts[i], pts[j], lim));
    }
    p.due[i] = i == 0 ? 1e18 : rng.uniform(lo, hi);
  }
  return p;
}

// All permutations, the same lexicographic objective.
RouteCost brute_force(const ScheduleProblem& p, std::vector<std::uint8_t>* best_order = nullptr) {
  std::vector<std::uint8_t> order(static_cast<std::size_t>(p.n));
  std::iota(order.begin(), order.end(), 1);
  RouteCost best{1e300, 1e300, 0, false};
  do {
    const RouteCost c = evaluate(p, order);
    if (c.lateness_s < best.lateness_s - 1e-9 ||
        (std::abs(c.lateness_s - best.lateness_s) <= 1e-9 && c.travel_s < best.travel_s - 1e-9)) {
      best = c;
      if (best_order != nullptr) *best_order = order;
    }
  } while (std::next_permutation(order.begin(), order.end()));
  return best;
}

}  // namespace

TEST(TimeCost, FirstLegMatchesHandCalculations) {
  const FlightLimits lim;  // 3 m/s, 1 m/s^2
  const Vec2 o(0, 0), east(1, 0);
  EXPECT_NEAR(first_leg_time_s(o, Vec2(0, 0), Vec2(2, 0), lim), 2.0, 1e-12);  // from rest, short
  EXPECT_NEAR(first_leg_time_s(o, Vec2(0, 0), Vec2(10, 0), lim), 3.0 + 5.5 / 3.0,
              1e-12);  // from rest, long
  EXPECT_NEAR(first_leg_time_s(o, 3.0 * east, Vec2(10, 0), lim), 10.0 / 3.0,
              1e-12);  // already at v_max towards
  EXPECT_NEAR(first_leg_time_s(o, east, Vec2(1, 0), lim), std::sqrt(3.0) - 1.0,
              1e-12);  // towards, short
  EXPECT_NEAR(first_leg_time_s(o, -2.0 * east, Vec2(10, 0), lim), 5.0 + 7.5 / 3.0, 1e-12);  // away
  EXPECT_NEAR(first_leg_time_s(o, Vec2(0, 3), Vec2(10, 0), lim), 3.0 + 5.5 / 3.0, 1e-12);  // across
  EXPECT_NEAR(first_leg_time_s(o, 4.0 * east, Vec2(9, 0), lim), 3.0, 1e-12);  // faster than v_max
  // The full velocity vector counts, not only x (the original's defect): moving along +y
  // towards a target due north is quicker than from rest.
  EXPECT_LT(first_leg_time_s(o, Vec2(0, 2), Vec2(0, 10), lim),
            first_leg_time_s(o, Vec2(0, 0), Vec2(0, 10), lim));
  EXPECT_NEAR(cruise_time_s(o, Vec2(3, 4), lim), 5.0 / 3.0, 1e-12);
}

TEST(Scheduler, ExactEqualsBruteForceOn500RandomInstances) {
  Rng rng(2024);
  auto scheduler = std::make_unique<Scheduler>();
  int feasible = 0, infeasible = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(8));
    const ScheduleProblem p = random_instance(rng, n, 2.0, 40.0);
    const ScheduleResult& r = scheduler->solve(p);
    const RouteCost bf = brute_force(p);
    ASSERT_TRUE(r.exact) << "trial " << trial;
    ASSERT_EQ(r.order.size(), static_cast<std::size_t>(n));
    EXPECT_NEAR(r.cost.lateness_s, bf.lateness_s, 1e-6) << "trial " << trial;
    EXPECT_NEAR(r.cost.travel_s, bf.travel_s, 1e-6) << "trial " << trial;
    (bf.feasible ? feasible : infeasible)++;
  }
  EXPECT_GT(feasible, 100);  // the instance mix covers both cases
  EXPECT_GT(infeasible, 100);
}

TEST(Scheduler, HeuristicIsWithinTwoPercentOfExactAndNeverLosesFeasibility) {
  Rng rng(77);
  auto exact = std::make_unique<Scheduler>();
  SchedulerConfig hcfg;
  hcfg.exact_max_stops = 0;  // force the heuristic
  auto heuristic = std::make_unique<Scheduler>(hcfg);
  double gap_sum = 0;
  int feasible = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const ScheduleProblem p = random_instance(rng, 12, 10.0, 60.0);
    const ScheduleResult e = exact->solve(p);
    const ScheduleResult& h = heuristic->solve(p);
    ASSERT_TRUE(e.exact);
    EXPECT_FALSE(h.exact);
    EXPECT_GE(h.cost.lateness_s, e.cost.lateness_s - 1e-6);
    if (e.cost.feasible) {
      EXPECT_TRUE(h.cost.feasible)
          << "trial " << trial << ": exact meets every deadline, the heuristic does not";
      ++feasible;
      gap_sum += h.cost.travel_s / e.cost.travel_s - 1.0;
    }
  }
  ASSERT_GT(feasible, 30);
  EXPECT_LE(gap_sum / feasible, 0.02) << "mean travel gap on feasible instances";
}

TEST(Scheduler, WhenNoOrderMeetsEveryDeadlineTotalLatenessIsMinimised) {
  // Three UGVs in a row along x, all due very soon; the UAV starts at the origin at rest.
  ScheduleProblem p;
  p.n = 3;
  const Vec2 pts[4] = {Vec2(0, 0), Vec2(9, 0), Vec2(-3, 0), Vec2(12, 0)};
  const FlightLimits lim;
  for (int i = 0; i <= 3; ++i) {
    for (int j = 0; j <= 3; ++j) {
      p.travel[i][j] = j == 0 ? 0.0
                              : (i == 0 ? first_leg_time_s(pts[0], Vec2::Zero(), pts[j], lim)
                                        : cruise_time_s(pts[i], pts[j], lim));
    }
  }
  p.due = {1e18, 2.0, 2.0, 6.0};
  std::vector<std::uint8_t> best;
  const RouteCost bf = brute_force(p, &best);
  ASSERT_FALSE(bf.feasible);
  auto scheduler = std::make_unique<Scheduler>();
  const ScheduleResult& r = scheduler->solve(p);
  EXPECT_FALSE(r.cost.feasible);
  EXPECT_NEAR(r.cost.lateness_s, bf.lateness_s, 1e-9);
  // Serving the earliest deadline first is worse here: it is not what we return.
  auto edf = std::make_unique<Scheduler>(SchedulerConfig{ScheduleMode::kNoScheduling});
  EXPECT_GT(edf->solve(p).cost.lateness_s, r.cost.lateness_s + 1.0);
}

TEST(Scheduler, AWeightedStopThatHasWaitedLongGoesFirst) {
  // A near stop due soon (in time if served first) and a far one already late. By lateness
  // alone the near one goes first (late 8 s at the far one vs 6 + 9 s the other way); once the
  // far UGV's lateness weighs 5x (it has asked for 40 s), it goes first (40 vs 30 + 9).
  ScheduleProblem p;
  p.n = 2;
  p.travel[0][1] = 2.0;
  p.travel[0][2] = 6.0;
  p.travel[1][2] = p.travel[2][1] = 6.0;
  p.due = {1e18, 3.0, 0.0};
  for (const int exact_max : {kExactMaxStops, 0}) {  // the exact solver and the heuristic
    SchedulerConfig c;
    c.exact_max_stops = exact_max;
    auto scheduler = std::make_unique<Scheduler>(c);
    const ScheduleResult& r = scheduler->solve(p);
    ASSERT_EQ(r.order.size(), 2U);
    EXPECT_EQ(r.order[0], 1);
    EXPECT_NEAR(r.cost.lateness_s, 8.0, 1e-9);
    p.weight[2] = 5.0;
    const ScheduleResult& w = scheduler->solve(p);
    ASSERT_EQ(w.order.size(), 2U);
    EXPECT_EQ(w.order[0], 2) << "exact_max_stops " << exact_max;
    EXPECT_NEAR(w.cost.lateness_s, 5.0 * 6.0 + 9.0, 1e-9);
    EXPECT_NEAR(w.cost.max_lateness_s, 9.0, 1e-9);  // not weighted
    p.weight[2] = 1.0;
  }
}

TEST(Scheduler, ExactEqualsBruteForceWithWeightedLateness) {
  Rng rng(77);
  auto scheduler = std::make_unique<Scheduler>();
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(8));
    ScheduleProblem p = random_instance(rng, n, 0.0, 20.0);
    for (int j = 1; j <= n; ++j)
      p.weight[j] = rng.uniform(1.0, 6.0);
    const ScheduleResult& r = scheduler->solve(p);
    const RouteCost bf = brute_force(p);
    ASSERT_TRUE(r.exact) << "trial " << trial;
    EXPECT_NEAR(r.cost.lateness_s, bf.lateness_s, 1e-6) << "trial " << trial;
    EXPECT_NEAR(r.cost.travel_s, bf.travel_s, 1e-6) << "trial " << trial;
  }
}

TEST(Scheduler, AblationsBehaveAsNamed) {
  Rng rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const ScheduleProblem p = random_instance(rng, 6, 1.0, 20.0);
    // No scheduling: smallest deadline first.
    auto edf = std::make_unique<Scheduler>(SchedulerConfig{ScheduleMode::kNoScheduling});
    const ScheduleResult& e = edf->solve(p);
    for (std::size_t i = 1; i < e.order.size(); ++i)
      EXPECT_LE(p.due[e.order[i - 1]], p.due[e.order[i]]);
    // No time windows: the shortest open route, whatever the lateness (reported honestly).
    ScheduleProblem relaxed = p;
    for (int k = 1; k <= p.n; ++k)
      relaxed.due[k] = 1e18;
    const RouteCost tsp = brute_force(relaxed);
    auto vrp = std::make_unique<Scheduler>(SchedulerConfig{ScheduleMode::kNoTimeWindows});
    const ScheduleResult& v = vrp->solve(p);
    EXPECT_NEAR(v.cost.travel_s, tsp.travel_s, 1e-6);
    EXPECT_NEAR(v.cost.lateness_s, evaluate(p, {v.order.begin(), v.order.end()}).lateness_s, 1e-12);
  }
}

TEST(Scheduler, ClosedRoutesWithReadyTimesAsInTspTwBenchmarks) {
  Rng rng(9);
  auto scheduler = std::make_unique<Scheduler>();
  for (int trial = 0; trial < 100; ++trial) {
    ScheduleProblem p;
    p.n = 1 + static_cast<int>(rng.below(7));
    p.closed = true;
    std::vector<Vec2> pts(static_cast<std::size_t>(p.n) + 1);
    for (auto& q : pts)
      q = Vec2(rng.uniform(0, 50), rng.uniform(0, 50));
    for (int i = 0; i <= p.n; ++i) {
      for (int j = 0; j <= p.n; ++j)
        p.travel[i][j] = std::floor((pts[i] - pts[j]).norm());
      p.ready[i] = i == 0 ? 0 : rng.uniform(0, 150);
      p.due[i] = i == 0 ? 400 : p.ready[i] + rng.uniform(10, 80);
    }
    const ScheduleResult& r = scheduler->solve(p);
    const RouteCost bf = brute_force(p);
    EXPECT_NEAR(r.cost.lateness_s, bf.lateness_s, 1e-6) << trial;
    EXPECT_NEAR(r.cost.travel_s, bf.travel_s, 1e-6) << trial;
  }
}

namespace {
bool no_worse(const RouteCost& a, const RouteCost& b) {  // a is at least as good as b
  return a.lateness_s < b.lateness_s - 1e-9 ||
         (a.lateness_s <= b.lateness_s + 1e-9 && a.travel_s <= b.travel_s + 1e-9);
}
}  // namespace

TEST(Scheduler, WarmStartsNeverWorsenThePlanKeepImprovingAndStayWithinBudget) {
  Rng rng(2024);
  SchedulerConfig cfg;
  cfg.work_budget = 20'000;  // small, so that there is something left to improve
  int improved = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const ScheduleProblem p = random_instance(rng, 40, 20.0, 120.0);
    auto scheduler = std::make_unique<Scheduler>(cfg);
    ScheduleResult last = scheduler->solve(p);
    const RouteCost first = last.cost;
    for (int step = 0; step < 10; ++step) {
      const auto order = last.order;
      const ScheduleResult& next = scheduler->solve(p, {order.begin(), order.end()});
      ASSERT_TRUE(no_worse(next.cost, last.cost)) << "trial " << trial << " step " << step;
      // One move's search may finish past the budget, never more than a few times it.
      EXPECT_LE(scheduler->last_work(), 3 * cfg.work_budget);
      EXPECT_EQ(next.age_steps,
                std::equal(next.order.begin(), next.order.end(), order.begin(), order.end())
                    ? last.age_steps + 1
                    : 0u);
      last = next;
    }
    improved += !no_worse(first, last.cost);
  }
  EXPECT_GE(improved, 5) << "warm steps should improve some of 20 plans found with a small budget";
}

TEST(Scheduler, AWarmPlanTakesANewUrgentRequestAtOnce) {
  Rng rng(5);
  SchedulerConfig cfg;
  cfg.exact_max_stops = 0;  // the heuristic's warm path, at a size the exact solver would take
  ScheduleProblem p = random_instance(rng, 8, 60.0, 120.0);
  auto scheduler = std::make_unique<Scheduler>(cfg);
  const auto plan = scheduler->solve(p).order;
  ASSERT_TRUE(scheduler->solve(p).cost.feasible);
  // Stop 9: due as soon as the UAV can get there directly.
  p.n = 9;
  for (int i = 0; i <= 9; ++i) {
    p.travel[i][9] = i == 9 ? 0.0 : 2.0;
    p.travel[9][i] = i == 0 ? 0.0 : 2.0;
  }
  p.due[9] = 2.0;
  const ScheduleResult& r = scheduler->solve(p, {plan.begin(), plan.end()});
  ASSERT_EQ(r.order.size(), 9u);
  EXPECT_EQ(r.order[0], 9);
  EXPECT_TRUE(r.cost.feasible);
}

TEST(Scheduler, AWarmOrderWithStaleOrRepeatedStopsIsCleanedNotTrusted) {
  Rng rng(6);
  SchedulerConfig cfg;
  cfg.exact_max_stops = 0;
  const ScheduleProblem p = random_instance(rng, 15, 30.0, 90.0);
  auto scheduler = std::make_unique<Scheduler>(cfg);
  const std::uint8_t junk[] = {0, 3, 3, 200, 16, 7, 255, 7, 1};
  const ScheduleResult& r = scheduler->solve(p, junk);
  ASSERT_EQ(r.order.size(), 15u);
  std::vector<std::uint8_t> sorted(r.order.begin(), r.order.end());
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i)
    EXPECT_EQ(sorted[i], i + 1);
}

TEST(Scheduler, TheReportedBoundNeverExceedsTheOptimum) {
  Rng rng(8);
  auto scheduler = std::make_unique<Scheduler>();
  for (int trial = 0; trial < 200; ++trial) {
    ScheduleProblem p = random_instance(rng, 6, 2.0, 40.0);
    p.closed = trial % 2 == 1;
    for (int j = 1; j <= p.n; ++j) {
      p.travel[j][0] = p.closed ? rng.uniform(0.5, 10.0) : 0.0;
      p.ready[j] = trial % 3 == 0 ? rng.uniform(0.0, 20.0) : 0.0;
    }
    double min_travel = 1e300;
    std::vector<std::uint8_t> order(static_cast<std::size_t>(p.n));
    std::iota(order.begin(), order.end(), 1);
    do {
      min_travel = std::min(min_travel, evaluate(p, order).travel_s);
    } while (std::next_permutation(order.begin(), order.end()));
    const RouteCost best = brute_force(p);
    const ScheduleResult& r = scheduler->solve(p);
    EXPECT_LE(r.bound.lateness_s, best.lateness_s + 1e-9) << "trial " << trial;
    EXPECT_LE(r.bound.travel_s, min_travel + 1e-9) << "trial " << trial;
    EXPECT_LE(r.bound.lateness_s, r.cost.lateness_s + 1e-9);
  }
}
