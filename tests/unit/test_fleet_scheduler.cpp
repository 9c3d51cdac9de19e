#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <vector>

#include "colag/common/random.hpp"
#include "colag/uav/fleet_scheduler.hpp"
#include "colag/uav/time_cost.hpp"

using namespace colag;
using namespace colag::uav;

namespace {

// K UAVs over a `side` m site, each with its own position and velocity (its first legs), stops
// at support points with deadlines in [lo, hi] s; a share of the stops held by some UAV.
std::unique_ptr<FleetProblem> random_fleet(Rng& rng, int n, int vehicles, double lo, double hi,
                                           double side = 27.0) {
  auto p = std::make_unique<FleetProblem>();
  p->n = n;
  p->vehicles = vehicles;
  const FlightLimits lim;
  std::vector<Vec2> stops(static_cast<std::size_t>(n) + 1);
  const double h = side / 2;
  for (auto& q : stops)
    q = Vec2(rng.uniform(-h, h), rng.uniform(-h, h));
  for (int i = 1; i <= n; ++i) {
    for (int j = 1; j <= n; ++j)
      p->travel[i][j] = i == j ? 0.0 : cruise_time_s(stops[i], stops[j], lim);
    p->due[i] = rng.uniform(lo, hi);
    p->owner[i] = static_cast<std::int16_t>(
        static_cast<int>(rng.below(static_cast<std::uint64_t>(vehicles) + 2)) -
        1);  // -1 .. vehicles: some free, some gone
  }
  for (int v = 0; v < vehicles; ++v) {
    const Vec2 at(rng.uniform(-h, h), rng.uniform(-h, h));
    const Vec2 vel(rng.uniform(-3, 3), rng.uniform(-3, 3));
    for (int j = 1; j <= n; ++j)
      p->first[static_cast<std::size_t>(v)][j] = first_leg_time_s(at, vel, stops[j], lim);
  }
  return p;
}

// The objective as the scheduler sees it, for comparisons: (lateness, travel), the switch cost
// on the travel (or on the waiting).
struct Objective {
  double primary, travel;
};
Objective objective(const FleetProblem& p, const FleetCost& c, bool on_waiting = false) {
  const double s = p.switch_cost_s * c.switches;
  return on_waiting ? Objective{c.lateness_s + s, c.travel_s}
                    : Objective{c.lateness_s, c.travel_s + s};
}
bool lexicographically_less(const Objective& a, const Objective& b) {
  if (std::abs(a.primary - b.primary) > 1e-9) return a.primary < b.primary;
  return a.travel < b.travel - 1e-9;
}

// Every split of the stops among the vehicles, every order of each share.
Objective brute_force(const FleetProblem& p, bool on_waiting) {
  const int n = p.n, k = p.vehicles;
  // Best order of every subset for every vehicle.
  std::vector<std::vector<Objective>> best(static_cast<std::size_t>(k),
                                           std::vector<Objective>(1U << n, {1e300, 1e300}));
  for (int v = 0; v < k; ++v) {
    for (std::uint32_t mask = 0; mask < (1U << n); ++mask) {
      std::vector<std::uint8_t> order;
      for (int j = 1; j <= n; ++j) {
        if (mask & (1U << (j - 1))) order.push_back(static_cast<std::uint8_t>(j));
      }
      int switches = 0;
      for (const std::uint8_t j : order)
        switches += p.owner[j] >= 0 && p.owner[j] < k && p.owner[j] != v ? 1 : 0;
      Objective& b = best[static_cast<std::size_t>(v)][mask];
      do {
        const RouteCost c = evaluate_route(p, v, order);
        const double sc = p.switch_cost_s * switches;
        const Objective o = on_waiting ? Objective{c.lateness_s + sc, c.travel_s}
                                       : Objective{c.lateness_s, c.travel_s + sc};
        if (lexicographically_less(o, b)) b = o;
      } while (std::next_permutation(order.begin(), order.end()));
    }
  }
  Objective out{1e300, 1e300};
  std::vector<int> who(static_cast<std::size_t>(n), 0);
  for (;;) {
    std::vector<std::uint32_t> share(static_cast<std::size_t>(k), 0);
    for (int j = 0; j < n; ++j)
      share[static_cast<std::size_t>(who[static_cast<std::size_t>(j)])] |= 1U << j;
    Objective total{0, 0};
    for (int v = 0; v < k; ++v) {
      total.primary +=
          best[static_cast<std::size_t>(v)][share[static_cast<std::size_t>(v)]].primary;
      total.travel += best[static_cast<std::size_t>(v)][share[static_cast<std::size_t>(v)]].travel;
    }
    if (lexicographically_less(total, out)) out = total;
    int j = 0;
    while (j < n && ++who[static_cast<std::size_t>(j)] == k)
      who[static_cast<std::size_t>(j++)] = 0;
    if (j == n) break;
  }
  return out;
}

// Every stop is in exactly one route, of a vehicle that flies.
void expect_every_stop_once(const FleetProblem& p, const FleetResult& r) {
  std::vector<int> seen(static_cast<std::size_t>(p.n) + 1, 0);
  for (std::size_t v = 0; v < kMaxVehicles; ++v) {
    if (static_cast<int>(v) >= p.vehicles) {
      EXPECT_TRUE(r.routes[v].empty());
    }
    for (const std::uint8_t k : r.routes[v]) {
      ASSERT_GE(k, 1);
      ASSERT_LE(k, p.n);
      ++seen[k];
      EXPECT_EQ(r.vehicle[k], static_cast<int>(v));
    }
  }
  for (int k = 1; k <= p.n; ++k)
    EXPECT_EQ(seen[static_cast<std::size_t>(k)], 1) << "stop " << k;
}

}  // namespace

TEST(FleetScheduler, ExactEqualsBruteForceOverEverySplitAndOrder) {
  Rng rng(77);
  auto fleet = std::make_unique<FleetScheduler>();
  int late = 0, on_time = 0, waiting_regime = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(6));
    const int k = 1 + static_cast<int>(rng.below(3));
    // Tight deadlines half the time: the lateness and the switch cost decide.
    const bool tight = trial % 2 == 0;
    auto p = random_fleet(rng, n, k, tight ? 2.0 : 10.0, tight ? 8.0 : 40.0);
    // Every other trial the last plan is the owners' (in stop order): when it is late, the
    // switch cost counts on the waiting.
    FleetRoutes last;
    for (int j = 1; j <= n; ++j) {
      if (p->owner[j] >= 0 && p->owner[j] < k)
        (void)last[static_cast<std::size_t>(p->owner[j])].push_back(static_cast<std::uint8_t>(j));
    }
    const FleetResult& r = fleet->solve(*p, trial % 4 < 2 ? &last : nullptr);
    ASSERT_TRUE(r.exact);
    expect_every_stop_once(*p, r);
    waiting_regime += r.switch_on_waiting ? 1 : 0;
    const Objective want = brute_force(*p, r.switch_on_waiting);
    const Objective got = objective(*p, r.cost, r.switch_on_waiting);
    EXPECT_NEAR(got.primary, want.primary, 1e-6) << "trial " << trial;
    EXPECT_NEAR(got.travel, want.travel, 1e-6) << "trial " << trial;
    (r.cost.feasible ? on_time : late)++;
  }
  EXPECT_GT(late, 20);  // late and on time, the switch cost on the waiting and on the travel
  EXPECT_GT(on_time, 20);
  EXPECT_GT(waiting_regime, 10);
}

TEST(FleetScheduler, HeuristicIsCloseToExactOnSmallFleets) {
  Rng rng(78);
  auto exact = std::make_unique<FleetScheduler>();
  auto heuristic = std::make_unique<FleetScheduler>(FleetSchedulerConfig{.exact_max_stops = 0});
  double gap_sum = 0.0;
  int compared = 0, lost_feasibility = 0, trials = 200;
  for (int trial = 0; trial < trials; ++trial) {
    const int n = 5 + static_cast<int>(rng.below(4));
    auto p = random_fleet(rng, n, 2 + static_cast<int>(rng.below(2)), 8.0, 40.0);
    const FleetResult& e = exact->solve(*p);
    const Objective best = objective(*p, e.cost);
    const bool e_feasible = e.cost.feasible;
    const FleetResult& h = heuristic->solve(*p);
    ASSERT_FALSE(h.exact);
    expect_every_stop_once(*p, h);
    const Objective got = objective(*p, h.cost);
    EXPECT_FALSE(lexicographically_less(got, best)) << "beat the optimum, trial " << trial;
    if (e_feasible && !h.cost.feasible) ++lost_feasibility;
    if (std::abs(got.primary - best.primary) <= 1e-9 && best.travel > 0) {
      gap_sum += got.travel / best.travel - 1.0;
      ++compared;
    }
  }
  EXPECT_GT(compared, trials * 3 / 4);
  EXPECT_LT(gap_sum / compared, 0.01);  // mean travel gap where the objective's first part ties
  EXPECT_LE(lost_feasibility, trials / 50);
}

// One UAV: the same problem as the single-vehicle scheduler's; exact up to 8 stops, and above
// that as good (the single one, exact to 12 stops, is the reference).
TEST(FleetScheduler, OneVehicleIsTheSingleUavProblem) {
  Rng rng(79);
  auto fleet = std::make_unique<FleetScheduler>();
  auto single = std::make_unique<Scheduler>();
  auto sp = std::make_unique<ScheduleProblem>();
  double gap = 0.0;
  int compared = 0;
  for (int trial = 0; trial < 60; ++trial) {
    auto p = random_fleet(rng, 1 + static_cast<int>(rng.below(12)), 1, 5.0, 40.0);
    p->owner.fill(-1);
    *sp = ScheduleProblem{};
    sp->n = p->n;
    for (int i = 0; i <= p->n; ++i) {
      for (int j = 1; j <= p->n; ++j)
        sp->travel[i][j] = i == 0 ? p->first[0][j] : p->travel[i][j];
      sp->due[i] = i == 0 ? 1e18 : p->due[i];
    }
    const RouteCost want = single->solve(*sp).cost;
    const FleetResult& r = fleet->solve(*p);
    if (p->n <= kFleetExactMaxStops) {
      EXPECT_TRUE(r.exact);
      EXPECT_NEAR(r.cost.lateness_s, want.lateness_s, 1e-6);
      EXPECT_NEAR(r.cost.travel_s, want.travel_s, 1e-6);
    } else if (std::abs(r.cost.lateness_s - want.lateness_s) <= 1e-6) {
      gap += r.cost.travel_s / want.travel_s - 1.0;
      ++compared;
    } else {
      EXPECT_LE(r.cost.lateness_s, 1.02 * want.lateness_s) << "trial " << trial;
    }
  }
  ASSERT_GT(compared, 5);
  EXPECT_LT(gap / compared, 0.01);
}

TEST(FleetScheduler, AssignmentsStayPutOnNoiseAndMoveOnlyWhenThatPays) {
  Rng rng(80);
  auto fleet = std::make_unique<FleetScheduler>();
  int switched = 0, returns = 0, steps = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = trial % 2 == 0 ? 7 : 24;  // the exact and the heuristic solver
    auto p = random_fleet(rng, n, 3, trial % 3 == 0 ? 3.0 : 15.0, 60.0);
    p->owner.fill(-1);
    FleetResult last = fleet->solve(*p);
    std::vector<int> left(static_cast<std::size_t>(n) + 1, -1);  // the vehicle each stop left
    // The next scheduling steps: everything moved a little (the UAVs flew on, the estimates
    // changed), the same stops; each step starts from the last plan and its assignment.
    // At the last step UAV 0 is suddenly 30 s further from everything (sent away): moving what
    // it holds pays.
    for (int step = 0; step < 11; ++step) {
      for (int k = 1; k <= n; ++k) {
        p->owner[k] = last.vehicle[k];
        p->due[k] += rng.uniform(-0.3, 0.3);
        for (std::size_t v = 0; v < 3; ++v)
          p->first[v][k] = std::max(0.0, p->first[v][k] + rng.uniform(-0.3, 0.3));
        if (step == 10) p->first[0][k] += 30.0;
      }
      const FleetCost kept = evaluate_fleet(*p, last.routes);  // the last plan, as it is now
      const FleetResult& r = fleet->solve(*p, &last.routes);
      expect_every_stop_once(*p, r);
      ++steps;
      // Never worse than keeping the last plan, switch cost included.
      const bool on_waiting = r.switch_on_waiting;
      EXPECT_EQ(on_waiting, !kept.feasible);
      EXPECT_FALSE(lexicographically_less(objective(*p, kept, on_waiting),
                                          objective(*p, r.cost, on_waiting)));
      int moves = 0;
      for (int k = 1; k <= n; ++k) {
        if (r.vehicle[k] == last.vehicle[k]) continue;
        ++moves;
        if (r.vehicle[k] == left[static_cast<std::size_t>(k)]) ++returns;  // back and forth
        left[static_cast<std::size_t>(k)] = last.vehicle[k];
      }
      EXPECT_EQ(moves, r.cost.switches);
      if (moves > 0) {
        ++switched;
        // A move pays for itself: a late plan saves more waiting than the switch cost of every
        // move; one on time keeps a deadline or saves more flying than that.
        const double cost = p->switch_cost_s * moves;
        if (on_waiting) {
          EXPECT_LT(r.cost.lateness_s + cost, kept.lateness_s - 1e-9);
        } else {
          EXPECT_TRUE(r.cost.lateness_s < kept.lateness_s - 1e-9 ||
                      r.cost.travel_s + cost < kept.travel_s - 1e-9);
        }
      }
      last = r;
    }
  }
  EXPECT_GT(switched, 10);          // moves happen when they pay (UAV 0 sent away) ...
  EXPECT_LE(returns, steps / 100);  // ... and a stop almost never goes back where it was
}

TEST(FleetScheduler, AVehicleThatIsGoneHasItsStopsTakenOver) {
  Rng rng(81);
  auto fleet = std::make_unique<FleetScheduler>();
  for (const int n : {6, 30}) {
    std::unique_ptr<FleetProblem> p;
    FleetResult before;
    for (int attempt = 0; attempt < 100 && before.routes[2].empty(); ++attempt) {
      p = random_fleet(rng, n, 3, 10.0, 60.0);  // until the third UAV holds stops
      p->owner.fill(-1);
      before = fleet->solve(*p);
    }
    ASSERT_FALSE(before.routes[2].empty());
    for (int k = 1; k <= n; ++k)
      p->owner[k] = before.vehicle[k];
    p->vehicles = 2;  // the third UAV went silent: its stops are free, the rest keep theirs
    const FleetResult& after = fleet->solve(*p, &before.routes);
    expect_every_stop_once(*p, after);
    int kept_moved = 0, orphans = 0;
    for (int k = 1; k <= n; ++k) {
      if (before.vehicle[k] == 2) ++orphans;
      if (before.vehicle[k] < 2 && after.vehicle[k] != before.vehicle[k]) ++kept_moved;
    }
    EXPECT_GT(orphans, 0);
    EXPECT_EQ(after.cost.switches, kept_moved);  // the orphans cost nothing to take over
  }
}

TEST(FleetScheduler, LargeFleetsStayWithinTheWorkBudgetAndServeEveryStop) {
  Rng rng(82);
  auto fleet = std::make_unique<FleetScheduler>();
  for (int trial = 0; trial < 10; ++trial) {
    auto p = random_fleet(rng, 64, 1 + trial % 4, 5.0, 120.0, 100.0);
    const FleetResult& r = fleet->solve(*p);
    expect_every_stop_once(*p, r);
    EXPECT_LE(fleet->last_work(), 3 * fleet->config().work_budget) << "trial " << trial;
    // Warm from its own plan: never worse.
    const FleetRoutes routes = r.routes;
    for (int k = 1; k <= p->n; ++k)
      p->owner[k] = r.vehicle[k];
    const FleetResult& w = fleet->solve(*p, &routes);
    EXPECT_FALSE(better(*p, evaluate_fleet(*p, routes), w.cost, w.switch_on_waiting));
  }
}
