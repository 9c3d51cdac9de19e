#pragma once
// Support scheduling for several UAVs: every live request is served by one of them, each UAV
// flying its own stops in its own order: a vehicle-routing problem with time windows for K
// vehicles, open routes, each vehicle starting where its UAV is, with its own first legs.
// Objective, lexicographic as for one UAV (scheduler.hpp): total weighted lateness, then total
// travel; plus `switch_cost_s` for every stop taken from the vehicle that held it in the last
// plan. The switch cost keeps assignments stable (two UAVs do not hand a UGV back and forth on
// noise); where it counts depends on the last plan:
// - on time: on the travel. A stop moves only to shorten the flying by more than switch_cost_s,
//   or to keep a deadline. (On the waiting it would forbid every move of a plan on time: a UAV
//   that took every request before it heard the others would keep them all.)
// - late: on the waiting. A stop moves only to save more than switch_cost_s of waiting (on the
//   travel, any gain in waiting, however small, would move it, and noise moves it back).
// A stop whose vehicle is gone is free.
// Solvers, both with static memory and bounded time:
// - exact, n <= exact_max_stops: every vehicle's best route over every subset of the stops (the
//   single-vehicle DP, Scheduler::subset_costs), then the best split of the stops among the
//   vehicles (a DP over subsets, K 3^n steps);
// - heuristic: the last plan's routes (stops of a vehicle no longer flying are free), the other
//   stops inserted by deadline where they cost least, then rounds of stop relocations and swaps
//   between routes, each route ordered by the single-vehicle scheduler (warm from its route).
#include <array>
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/random.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/uav/scheduler.hpp"

namespace colag::uav {

inline constexpr std::size_t kMaxVehicles = limits::kMaxUavs;
inline constexpr int kFleetExactMaxStops = 8;

using Route = StaticVector<std::uint8_t, kMaxStops>;  // stop numbers in visiting order
using FleetRoutes = std::array<Route, kMaxVehicles>;

struct FleetProblem {
  int n = 0;         // stops 1..n
  int vehicles = 1;  // 1..kMaxVehicles
  // Seconds from stop i to stop j (i, j >= 1; row and column 0 unused).
  std::array<std::array<double, kMaxStops + 1>, kMaxStops + 1> travel{};
  std::array<std::array<double, kMaxStops + 1>, kMaxVehicles> first{};  // vehicle v -> stop j
  std::array<double, kMaxStops + 1> ready{};
  std::array<double, kMaxStops + 1> due{};
  std::array<double, kMaxStops + 1> weight = detail::ones();  // see ScheduleProblem
  // The vehicle that held stop j in the last plan; -1: none (new, or its vehicle is gone).
  std::array<std::int16_t, kMaxStops + 1> owner = [] {
    std::array<std::int16_t, kMaxStops + 1> a{};
    a.fill(-1);
    return a;
  }();
  double switch_cost_s = 2.0;
};

struct FleetCost {
  double lateness_s = 0.0;  // weighted, without the switch cost
  double travel_s = 0.0;
  double max_lateness_s = 0.0;  // not weighted
  int switches = 0;             // stops taken from the vehicle that held them
  bool feasible = true;         // every stop on time
};

struct FleetResult {
  FleetRoutes routes;                                 // per vehicle
  std::array<std::int16_t, kMaxStops + 1> vehicle{};  // per stop: who serves it
  std::array<double, kMaxStops + 1> arrival{};        // per stop
  FleetCost cost;
  bool exact = false;              // proven optimal for the objective
  bool switch_on_waiting = false;  // the switch cost counted on the waiting (the last plan late)
};

// Vehicle v flying `route`: its lateness and travel (arrivals per stop into `arrival` if given).
RouteCost evaluate_route(const FleetProblem& p, int v, std::span<const std::uint8_t> route,
                         double* arrival = nullptr);
// The whole plan by the objective (routes of vehicles >= p.vehicles must be empty).
FleetCost evaluate_fleet(const FleetProblem& p, const FleetRoutes& routes);
// a better than b by the objective, the switch cost counted on the waiting or on the travel.
bool better(const FleetProblem& p, const FleetCost& a, const FleetCost& b, bool on_waiting);

struct FleetSchedulerConfig {
  int exact_max_stops = kFleetExactMaxStops;
  // Heuristic effort in route evaluations (one unit per stop looked at), moves between routes and
  // the routes' own search together; about 1 ms on a desktop core, as for one UAV.
  std::uint64_t work_budget = 200'000;
  int rounds = 3;  // descents between routes, each followed by ordering every route
  // Each route's ordering gets an equal share of what is left of the budget, at least this.
  std::uint64_t route_budget_min = 5'000;
  // A route is ordered exactly up to this many stops (the DP's time grows as 2^n n^2: at 12 stops
  // and late, ~2 ms a route; a fleet orders its routes several times a step).
  int route_exact_max_stops = 8;
  std::uint64_t seed = 0x5eed;  // of the routes' own search
};

class FleetScheduler {
 public:
  // `labels`: the exact route solver's memory, shared (Scheduler); own memory without it.
  explicit FleetScheduler(const FleetSchedulerConfig& config = {}, ExactLabels* labels = nullptr);
  // `warm`: the last plan's routes in this problem's stop numbers (stops out of range or
  // repeated, and routes of vehicles >= p.vehicles, are ignored): the search starts from it.
  const FleetResult& solve(const FleetProblem& p, const FleetRoutes* warm = nullptr);
  const FleetSchedulerConfig& config() const { return config_; }
  std::uint64_t last_work() const { return work_; }

 private:
  bool solve_exact(const FleetProblem& p);
  void solve_heuristic(const FleetProblem& p, const FleetRoutes* warm);
  // Inserts `stop` where it costs least over every vehicle and position.
  void insert(const FleetProblem& p, std::uint8_t stop);
  // Each applies every improving move it finds: one stop to another route (at its best place),
  // or two stops of two routes exchanged.
  bool relocate_pass(const FleetProblem& p);
  bool swap_pass(const FleetProblem& p);
  // Two routes exchange their tails (2-opt*): a1 a2, b1 b2 -> a1 b2, b1 a2.
  bool tails_pass(const FleetProblem& p);
  // Routes a and b as they are (their objective, summed), and the exchange that makes them
  // scratch_ and other_: taken, and `now` updated, if that is better.
  RouteCost pair_cost(const FleetProblem& p, std::size_t a, std::size_t b);
  bool exchange_if_better(const FleetProblem& p, std::size_t a, std::size_t b, RouteCost& now);
  void descend(const FleetProblem& p);  // the three passes until none moves a stop
  // Iterated search on the split: a kick moves 1-2 random stops to random places in other
  // routes, a descent follows; kept if better, else undone; until `patience` idle kicks or the
  // budget is spent.
  void iterate(const FleetProblem& p);
  // Each route by the single-vehicle scheduler; `rounds_left` (this one included) share the
  // budget that is left.
  void order_routes(const FleetProblem& p, int rounds_left);
  // Vehicle v's problem over `stops` (node k: stops[k - 1]), into sub_.
  void route_problem(const FleetProblem& p, int v, std::span<const std::uint8_t> stops);
  // Route v's objective: its lateness, its travel plus its switch cost (counts work).
  RouteCost route_cost(const FleetProblem& p, int v, std::span<const std::uint8_t> route);
  void finish(bool exact);

  FleetSchedulerConfig config_;
  Scheduler scheduler_;   // one for every vehicle's route, in turn
  FleetProblem problem_;  // the problem as solved (n and vehicles in range)
  ScheduleProblem sub_;
  FleetResult result_;
  FleetRoutes routes_;
  Route scratch_, other_;
  FleetRoutes best_;
  std::uint64_t work_ = 0;
  std::uint64_t limit_ = 0;  // the work this part of the solve may reach (a share of the budget)
  Rng rng_{0};               // the kicks: reseeded by a cold solve, continued by warm ones
  bool on_waiting_ = false;  // this solve's switch cost counts on the waiting
  // Exact: per vehicle, the best route over each subset; then the best split.
  static constexpr std::size_t kSubsets = std::size_t{1} << kFleetExactMaxStops;
  std::array<std::array<RouteCost, kSubsets>, kMaxVehicles> subset_{};
  std::array<std::array<RouteCost, kSubsets>, kMaxVehicles + 1> split_{};
  std::array<std::array<std::uint16_t, kSubsets>, kMaxVehicles + 1> take_{};
};

}  // namespace colag::uav
