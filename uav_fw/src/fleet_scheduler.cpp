#include "colag/uav/fleet_scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colag::uav {

namespace {

constexpr double kEps = 1e-9;
constexpr double kInf = std::numeric_limits<double>::infinity();

// (lateness, travel) pairs, lexicographic; the travel holds the switch cost.
bool less(const RouteCost& a, const RouteCost& b) {
  if (std::abs(a.lateness_s - b.lateness_s) > kEps) return a.lateness_s < b.lateness_s;
  return a.travel_s < b.travel_s - kEps;
}

RouteCost sum(const RouteCost& a, const RouteCost& b) {
  return {a.lateness_s + b.lateness_s, a.travel_s + b.travel_s, 0.0, a.feasible && b.feasible};
}

int switches(const FleetProblem& p, int v, std::span<const std::uint8_t> route) {
  int s = 0;
  for (const std::uint8_t k : route)
    s += p.owner[k] >= 0 && p.owner[k] != v ? 1 : 0;
  return s;
}

}  // namespace

RouteCost evaluate_route(const FleetProblem& p, int v, std::span<const std::uint8_t> route,
                         double* arrival) {
  RouteCost c;
  double t = 0.0;
  int prev = -1;
  for (const std::uint8_t k : route) {
    const double leg = prev < 0 ? p.first[static_cast<std::size_t>(v)][k] : p.travel[prev][k];
    c.travel_s += leg;
    t = std::max(p.ready[k], t + leg);
    const double l = std::max(0.0, t - p.due[k]);
    c.lateness_s += p.weight[k] * l;
    c.max_lateness_s = std::max(c.max_lateness_s, l);
    if (arrival != nullptr) arrival[k] = t;
    prev = k;
  }
  c.feasible = c.lateness_s <= kEps;
  return c;
}

FleetCost evaluate_fleet(const FleetProblem& p, const FleetRoutes& routes) {
  FleetCost f;
  for (int v = 0; v < p.vehicles; ++v) {
    const Route& r = routes[static_cast<std::size_t>(v)];
    const RouteCost c = evaluate_route(p, v, {r.begin(), r.end()});
    f.lateness_s += c.lateness_s;
    f.travel_s += c.travel_s;
    f.max_lateness_s = std::max(f.max_lateness_s, c.max_lateness_s);
    f.switches += switches(p, v, {r.begin(), r.end()});
  }
  f.feasible = f.lateness_s <= kEps;
  return f;
}

bool better(const FleetProblem& p, const FleetCost& a, const FleetCost& b, bool on_waiting) {
  const double ca = p.switch_cost_s * a.switches, cb = p.switch_cost_s * b.switches;
  if (on_waiting) {
    return less({a.lateness_s + ca, a.travel_s, 0.0, true},
                {b.lateness_s + cb, b.travel_s, 0.0, true});
  }
  return less({a.lateness_s, a.travel_s + ca, 0.0, true},
              {b.lateness_s, b.travel_s + cb, 0.0, true});
}

FleetScheduler::FleetScheduler(const FleetSchedulerConfig& config, ExactLabels* labels)
    : config_(config),
      scheduler_(SchedulerConfig{.exact_max_stops = config.route_exact_max_stops,
                                 .work_budget = config.route_budget_min,
                                 .seed = config.seed},
                 labels) {}

const FleetResult& FleetScheduler::solve(const FleetProblem& problem, const FleetRoutes* warm) {
  work_ = 0;
  limit_ = config_.work_budget;
  problem_ = problem;
  FleetProblem& p = problem_;
  p.n = std::clamp(p.n, 0, static_cast<int>(kMaxStops));
  p.vehicles = std::clamp(p.vehicles, 1, static_cast<int>(kMaxVehicles));
  p.switch_cost_s = std::isfinite(p.switch_cost_s) ? std::max(0.0, p.switch_cost_s) : 0.0;
  for (int k = 1; k <= p.n; ++k) {
    if (p.owner[k] >= p.vehicles) p.owner[k] = -1;  // its vehicle is gone: free
  }
  // Where the switch cost counts: on the waiting if the last plan is late, else on the flying.
  on_waiting_ = false;
  if (warm != nullptr) {
    for (int v = 0; v < p.vehicles; ++v) {
      scratch_.clear();
      for (const std::uint8_t k : (*warm)[static_cast<std::size_t>(v)]) {
        if (k >= 1 && k <= p.n) (void)scratch_.push_back(k);
      }
      on_waiting_ =
          on_waiting_ || !evaluate_route(p, v, {scratch_.begin(), scratch_.end()}).feasible;
    }
  }
  for (Route& r : routes_)
    r.clear();
  if (p.n == 0) {
    finish(true);
    return result_;
  }
  const bool small = p.n <= std::min(config_.exact_max_stops, kFleetExactMaxStops);
  if (!small || !solve_exact(p)) solve_heuristic(p, warm);
  return result_;
}

void FleetScheduler::route_problem(const FleetProblem& p, int v,
                                   std::span<const std::uint8_t> stops) {
  const auto m = static_cast<int>(stops.size());
  sub_.n = m;
  sub_.closed = false;
  sub_.due[0] = kInf;
  for (int i = 0; i <= m; ++i) {
    const std::uint8_t a = i == 0 ? 0 : stops[static_cast<std::size_t>(i - 1)];
    for (int j = 1; j <= m; ++j) {
      const std::uint8_t b = stops[static_cast<std::size_t>(j - 1)];
      sub_.travel[i][j] = i == 0 ? p.first[static_cast<std::size_t>(v)][b] : p.travel[a][b];
    }
    sub_.travel[i][0] = 0.0;
    if (i == 0) continue;
    sub_.ready[i] = p.ready[a];
    sub_.due[i] = p.due[a];
    sub_.weight[i] = p.weight[a];
  }
}

RouteCost FleetScheduler::route_cost(const FleetProblem& p, int v,
                                     std::span<const std::uint8_t> route) {
  work_ += route.size() + 1;
  RouteCost c = evaluate_route(p, v, route);
  (on_waiting_ ? c.lateness_s : c.travel_s) += p.switch_cost_s * switches(p, v, route);
  return c;
}

// --- exact -------------------------------------------------------------------------------------

bool FleetScheduler::solve_exact(const FleetProblem& p) {
  const int n = p.n, vehicles = p.vehicles;
  const std::uint32_t full = (1U << n) - 1U;
  StaticVector<std::uint8_t, kMaxStops> all;
  for (int k = 1; k <= n; ++k)
    (void)all.push_back(static_cast<std::uint8_t>(k));
  for (int v = 0; v < vehicles; ++v) {
    auto& costs = subset_[static_cast<std::size_t>(v)];
    route_problem(p, v, {all.begin(), all.end()});
    if (!scheduler_.subset_costs(sub_, {costs.data(), std::size_t{1} << n})) return false;
    for (std::uint32_t mask = 1; mask <= full; ++mask) {
      int taken = 0;
      for (int k = 1; k <= n; ++k)
        taken += (mask & (1U << (k - 1))) != 0 && p.owner[k] >= 0 && p.owner[k] != v ? 1 : 0;
      (on_waiting_ ? costs[mask].lateness_s : costs[mask].travel_s) += p.switch_cost_s * taken;
    }
  }
  // split_[v][S]: the best way for vehicles v.. to serve the stops S; take_[v][S]: v's share.
  const auto last = static_cast<std::size_t>(vehicles);
  split_[last].fill(RouteCost{kInf, kInf, 0.0, false});
  split_[last][0] = RouteCost{};
  for (std::size_t v = last; v-- > 0;) {
    for (std::uint32_t set = 0; set <= full; ++set) {
      RouteCost best{kInf, kInf, 0.0, false};
      std::uint32_t best_share = 0;
      for (std::uint32_t share = set;; share = (share - 1) & set) {
        const RouteCost rest = split_[v + 1][set ^ share];
        if (rest.travel_s < kInf) {
          const RouteCost c = sum(subset_[v][share], rest);
          if (less(c, best)) {
            best = c;
            best_share = share;
          }
        }
        if (share == 0) break;
      }
      split_[v][set] = best;
      take_[v][set] = static_cast<std::uint16_t>(best_share);
    }
  }
  // Each vehicle's share, ordered by the single-vehicle scheduler (exact at this size).
  std::uint32_t set = full;
  bool exact = true;
  for (int v = 0; v < vehicles; ++v) {
    const std::uint32_t share = take_[static_cast<std::size_t>(v)][set];
    set ^= share;
    scratch_.clear();
    for (int k = 1; k <= n; ++k) {
      if ((share & (1U << (k - 1))) != 0) (void)scratch_.push_back(static_cast<std::uint8_t>(k));
    }
    Route& route = routes_[static_cast<std::size_t>(v)];
    if (scratch_.empty()) continue;
    route_problem(p, v, {scratch_.begin(), scratch_.end()});
    const ScheduleResult& r = scheduler_.solve(sub_);
    exact = exact && r.exact;
    for (const std::uint8_t k : r.order)
      (void)route.push_back(scratch_[k - 1u]);
  }
  finish(exact);
  return true;
}

// --- heuristic -----------------------------------------------------------------------------------

void FleetScheduler::insert(const FleetProblem& p, std::uint8_t stop) {
  std::size_t best_v = 0, best_at = 0;
  RouteCost best_delta{kInf, kInf, 0.0, false};
  for (std::size_t v = 0; v < static_cast<std::size_t>(p.vehicles); ++v) {
    const Route& r = routes_[v];
    const int vi = static_cast<int>(v);
    const RouteCost before = route_cost(p, vi, {r.begin(), r.end()});
    for (std::size_t at = 0; at <= r.size(); ++at) {
      scratch_ = r;
      (void)scratch_.insert_at(at, stop);
      const RouteCost after = route_cost(p, vi, {scratch_.begin(), scratch_.end()});
      const RouteCost delta{after.lateness_s - before.lateness_s, after.travel_s - before.travel_s,
                            0.0, true};
      if (less(delta, best_delta)) {
        best_delta = delta;
        best_v = v;
        best_at = at;
      }
    }
  }
  Route& r = routes_[best_v];
  (void)r.insert_at(best_at, stop);
}

bool FleetScheduler::relocate_pass(const FleetProblem& p) {
  bool moved = false;
  const auto vehicles = static_cast<std::size_t>(p.vehicles);
  for (std::size_t a = 0; a < vehicles; ++a) {
    for (std::size_t i = 0; i < routes_[a].size() && work_ < limit_;) {
      Route& from = routes_[a];
      const std::uint8_t s = from[i];
      const RouteCost a_now = route_cost(p, static_cast<int>(a), {from.begin(), from.end()});
      other_ = from;
      other_.erase_at(i);
      const RouteCost a_then = route_cost(p, static_cast<int>(a), {other_.begin(), other_.end()});
      std::size_t best_b = vehicles, best_at = 0;
      RouteCost best_gain{0.0, 0.0, 0.0, true};
      for (std::size_t b = 0; b < vehicles; ++b) {
        if (b == a) continue;
        const Route& to = routes_[b];
        const auto bi = static_cast<int>(b);
        const RouteCost b_now = route_cost(p, bi, {to.begin(), to.end()});
        for (std::size_t at = 0; at <= to.size(); ++at) {
          scratch_ = to;
          (void)scratch_.insert_at(at, s);
          const RouteCost b_then = route_cost(p, bi, {scratch_.begin(), scratch_.end()});
          // What the move saves: (now) - (then), better if it beats the best saving so far.
          const RouteCost gain{
              a_now.lateness_s + b_now.lateness_s - a_then.lateness_s - b_then.lateness_s,
              a_now.travel_s + b_now.travel_s - a_then.travel_s - b_then.travel_s, 0.0, true};
          if (less(best_gain, gain)) {
            best_gain = gain;
            best_b = b;
            best_at = at;
          }
        }
      }
      if (best_b == vehicles) {
        ++i;
        continue;
      }
      from = other_;
      Route& to = routes_[best_b];
      (void)to.insert_at(best_at, s);
      moved = true;  // position i now holds the next stop
    }
  }
  return moved;
}

bool FleetScheduler::exchange_if_better(const FleetProblem& p, std::size_t a, std::size_t b,
                                        RouteCost& now) {
  const RouteCost then = sum(route_cost(p, static_cast<int>(a), {scratch_.begin(), scratch_.end()}),
                             route_cost(p, static_cast<int>(b), {other_.begin(), other_.end()}));
  if (!less(then, now)) return false;
  routes_[a] = scratch_;
  routes_[b] = other_;
  now = then;
  return true;
}

RouteCost FleetScheduler::pair_cost(const FleetProblem& p, std::size_t a, std::size_t b) {
  return sum(route_cost(p, static_cast<int>(a), {routes_[a].begin(), routes_[a].end()}),
             route_cost(p, static_cast<int>(b), {routes_[b].begin(), routes_[b].end()}));
}

bool FleetScheduler::swap_pass(const FleetProblem& p) {
  bool moved = false;
  const auto vehicles = static_cast<std::size_t>(p.vehicles);
  for (std::size_t a = 0; a < vehicles; ++a) {
    for (std::size_t b = a + 1; b < vehicles; ++b) {
      RouteCost now = pair_cost(p, a, b);
      for (std::size_t i = 0; i < routes_[a].size(); ++i) {
        for (std::size_t j = 0; j < routes_[b].size() && work_ < limit_; ++j) {
          scratch_ = routes_[a];
          other_ = routes_[b];
          std::swap(scratch_[i], other_[j]);
          moved = exchange_if_better(p, a, b, now) || moved;
        }
      }
    }
  }
  return moved;
}

bool FleetScheduler::tails_pass(const FleetProblem& p) {
  bool moved = false;
  const auto vehicles = static_cast<std::size_t>(p.vehicles);
  for (std::size_t a = 0; a < vehicles; ++a) {
    for (std::size_t b = a + 1; b < vehicles; ++b) {
      const Route& ra = routes_[a];
      const Route& rb = routes_[b];
      RouteCost now = pair_cost(p, a, b);
      for (std::size_t i = 0; i <= ra.size(); ++i) {
        for (std::size_t j = 0; j <= rb.size(); ++j) {
          if (work_ >= limit_) return moved;
          if (i == ra.size() && j == rb.size()) continue;  // nothing exchanged
          scratch_.clear();
          other_.clear();
          for (std::size_t k = 0; k < i; ++k)
            (void)scratch_.push_back(ra[k]);
          for (std::size_t k = j; k < rb.size(); ++k)
            (void)scratch_.push_back(rb[k]);
          for (std::size_t k = 0; k < j; ++k)
            (void)other_.push_back(rb[k]);
          for (std::size_t k = i; k < ra.size(); ++k)
            (void)other_.push_back(ra[k]);
          moved = exchange_if_better(p, a, b, now) || moved;
        }
      }
    }
  }
  return moved;
}

void FleetScheduler::descend(const FleetProblem& p) {
  for (;;) {
    bool moved = relocate_pass(p);
    moved = swap_pass(p) || moved;
    moved = tails_pass(p) || moved;
    if (!moved || work_ >= limit_) return;
  }
}

void FleetScheduler::iterate(const FleetProblem& p) {
  best_ = routes_;
  FleetCost best = evaluate_fleet(p, routes_);
  const int patience = std::max(1, p.n);
  const auto vehicles = static_cast<std::uint64_t>(p.vehicles);
  for (int idle = 0; idle < patience && work_ < limit_;) {
    const std::uint64_t kicks = 1 + rng_.below(2);
    for (std::uint64_t k = 0; k < kicks; ++k) {
      const std::size_t a = rng_.below(vehicles);
      if (routes_[a].empty()) continue;
      const std::size_t b = (a + 1 + rng_.below(vehicles - 1)) % vehicles;
      const std::size_t i = rng_.below(routes_[a].size());
      const std::uint8_t stop = routes_[a][i];
      routes_[a].erase_at(i);
      (void)routes_[b].insert_at(rng_.below(routes_[b].size() + 1), stop);
    }
    descend(p);
    work_ += static_cast<std::uint64_t>(p.n);
    const FleetCost c = evaluate_fleet(p, routes_);
    if (better(p, c, best, on_waiting_)) {
      best_ = routes_;
      best = c;
      idle = 0;
    } else {
      routes_ = best_;
      ++idle;
    }
  }
  routes_ = best_;
}

void FleetScheduler::order_routes(const FleetProblem& p, int rounds_left) {
  std::size_t routes_left = 0;
  for (std::size_t v = 0; v < static_cast<std::size_t>(p.vehicles); ++v)
    routes_left += routes_[v].size() >= 2 ? 1 : 0;
  for (std::size_t v = 0; v < static_cast<std::size_t>(p.vehicles); ++v) {
    Route& r = routes_[v];
    if (r.size() < 2) continue;
    const std::uint64_t left = limit_ > work_ ? limit_ - work_ : 0;
    scheduler_.set_work_budget(
        std::max(config_.route_budget_min,
                 left / (routes_left-- * static_cast<std::uint64_t>(rounds_left))));
    route_problem(p, static_cast<int>(v), {r.begin(), r.end()});
    StaticVector<std::uint8_t, kMaxStops> warm;
    for (std::size_t k = 1; k <= r.size(); ++k)
      (void)warm.push_back(static_cast<std::uint8_t>(k));
    const ScheduleResult& s = scheduler_.solve(sub_, {warm.begin(), warm.end()});
    work_ += scheduler_.last_work();
    scratch_.clear();
    for (const std::uint8_t k : s.order)
      (void)scratch_.push_back(r[k - 1u]);
    r = scratch_;
  }
}

void FleetScheduler::solve_heuristic(const FleetProblem& p, const FleetRoutes* warm) {
  std::array<bool, kMaxStops + 1> placed{};
  if (warm != nullptr) {
    for (std::size_t v = 0; v < static_cast<std::size_t>(p.vehicles); ++v) {
      for (const std::uint8_t k : (*warm)[v]) {
        if (k < 1 || k > p.n || placed[k]) continue;
        placed[k] = true;
        (void)routes_[v].push_back(k);
      }
    }
  }
  StaticVector<std::uint8_t, kMaxStops> rest;
  for (int k = 1; k <= p.n; ++k) {
    if (!placed[k]) (void)rest.push_back(static_cast<std::uint8_t>(k));
  }
  std::sort(rest.begin(), rest.end(), [&](std::uint8_t a, std::uint8_t b) {
    return p.due[a] != p.due[b] ? p.due[a] < p.due[b] : a < b;
  });
  for (const std::uint8_t k : rest)
    insert(p, k);
  if (p.vehicles == 1) {  // nothing moves between routes: its route gets the whole budget
    order_routes(p, 1);
    finish(false);
    return;
  }
  if (warm == nullptr) rng_ = Rng(config_.seed + static_cast<std::uint64_t>(p.n));
  // Half the budget for the split (descents, then kicks), the rest for the routes' orders.
  limit_ = config_.work_budget / 2;
  descend(p);
  iterate(p);
  limit_ = config_.work_budget;
  for (int round = 0; round < config_.rounds && work_ < limit_; ++round) {
    order_routes(p, config_.rounds - round);
    const FleetCost before = evaluate_fleet(p, routes_);
    descend(p);
    if (!better(p, evaluate_fleet(p, routes_), before, on_waiting_)) break;
  }
  finish(false);
}

void FleetScheduler::finish(bool exact) {
  const FleetProblem& p = problem_;
  result_.routes = routes_;
  result_.vehicle.fill(-1);
  result_.arrival.fill(0.0);
  for (int v = 0; v < p.vehicles; ++v) {
    const Route& r = routes_[static_cast<std::size_t>(v)];
    (void)evaluate_route(p, v, {r.begin(), r.end()}, result_.arrival.data());
    for (const std::uint8_t k : r)
      result_.vehicle[k] = static_cast<std::int16_t>(v);
  }
  result_.cost = evaluate_fleet(p, routes_);
  result_.exact = exact;
  result_.switch_on_waiting = on_waiting_;
}

}  // namespace colag::uav
