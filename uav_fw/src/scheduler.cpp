#include "colag/uav/scheduler.hpp"

#include "colag/common/random.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colag::uav {

namespace {
constexpr double kEps = 1e-9;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kRepairReach = 10;  // positions a stop moves on a route that is late
}  // namespace

RouteCost evaluate(const ScheduleProblem& p, std::span<const std::uint8_t> order, double* arrival) {
  RouteCost c;
  double t = 0.0;
  std::uint8_t prev = 0;
  const auto late = [&](double start, std::uint8_t k) {
    const double l = std::max(0.0, start - p.due[k]);
    c.lateness_s += p.weight[k] * l;
    c.max_lateness_s = std::max(c.max_lateness_s, l);
  };
  for (const std::uint8_t k : order) {
    c.travel_s += p.travel[prev][k];
    t = std::max(p.ready[k], t + p.travel[prev][k]);
    late(t, k);
    if (arrival != nullptr) arrival[k] = t;
    prev = k;
  }
  if (p.closed) {
    c.travel_s += p.travel[prev][0];
    late(t + p.travel[prev][0], 0);
  }
  c.feasible = c.lateness_s <= kEps;
  return c;
}

RouteCost Scheduler::cost(const ScheduleProblem& p, std::span<const std::uint8_t> order) {
  work_ += order.size() + 1;
  return evaluate(p, order);
}

bool Scheduler::better(const RouteCost& a, const RouteCost& b) const {
  if (std::abs(a.lateness_s - b.lateness_s) > kEps) return a.lateness_s < b.lateness_s;
  return a.travel_s < b.travel_s - kEps;
}

void Scheduler::finish(const ScheduleProblem& p, std::span<const std::uint8_t> order,
                       ScheduleResult& out) const {
  out.order.clear();
  for (const std::uint8_t k : order)
    (void)out.order.push_back(k);
  out.cost = evaluate(p, order, out.arrival.data());
}

namespace {

// Lower bounds: every stop is entered once, by some leg no shorter than its quickest way in, and
// reached no sooner than the quickest path from the start (Dijkstra over the dense matrix).
RouteCost lower_bound(const ScheduleProblem& p) {
  RouteCost b;
  const int n = p.n;
  for (int j = p.closed ? 0 : 1; j <= n; ++j) {
    double in = kInf;
    for (int i = j == 0 ? 1 : 0; i <= n; ++i) {
      if (i != j) in = std::min(in, p.travel[i][j]);
    }
    b.travel_s += in == kInf ? 0.0 : in;
  }
  std::array<double, kMaxStops + 1> earliest{};
  std::array<bool, kMaxStops + 1> done{};
  earliest.fill(kInf);
  earliest[0] = 0.0;
  for (int round = 0; round <= n; ++round) {
    int u = -1;
    for (int i = 0; i <= n; ++i) {
      if (!done[i] && (u < 0 || earliest[i] < earliest[u])) u = i;
    }
    done[u] = true;
    for (int j = 1; j <= n; ++j) {
      if (!done[j]) earliest[j] = std::min(earliest[j], earliest[u] + p.travel[u][j]);
    }
  }
  for (int j = 1; j <= n; ++j) {
    const double l = std::max(0.0, std::max(p.ready[j], earliest[j]) - p.due[j]);
    b.lateness_s += p.weight[j] * l;
    b.max_lateness_s = std::max(b.max_lateness_s, l);
  }
  b.feasible = b.lateness_s <= kEps;
  return b;
}

}  // namespace

const ScheduleResult& Scheduler::solve(const ScheduleProblem& problem,
                                       std::span<const std::uint8_t> warm) {
  result_ = ScheduleResult{};
  work_ = 0;
  const int n = std::clamp(problem.n, 0, static_cast<int>(kMaxStops));
  working_ = problem;
  working_.n = n;
  StaticVector<std::uint8_t, kMaxStops> by_deadline;
  for (int k = 1; k <= n; ++k)
    (void)by_deadline.push_back(static_cast<std::uint8_t>(k));
  // std::sort with a total order (the key, then the stop number): as deterministic as a
  // stable sort, and unlike std::stable_sort it never allocates a temporary buffer.
  std::sort(by_deadline.begin(), by_deadline.end(), [&](std::uint8_t a, std::uint8_t b) {
    return problem.due[a] != problem.due[b] ? problem.due[a] < problem.due[b] : a < b;
  });
  if (n == 0 || config_.mode == ScheduleMode::kNoScheduling) {
    finish(problem, {by_deadline.begin(), by_deadline.end()}, result_);
    age_steps_ = 0;
    return result_;
  }
  if (config_.mode == ScheduleMode::kNoTimeWindows) {
    for (int k = 0; k <= n; ++k)
      working_.due[k] = kInf;
  }
  const bool small = n <= std::min(config_.exact_max_stops, kExactMaxStops);
  if (!small || !solve_exact(working_, true, nullptr, result_)) {
    // No order meets every deadline (or too many stops for the exact solver): the heuristic
    // gives an incumbent; the exact solver, pruning against it, either beats it or proves it.
    solve_heuristic(working_, !small, warm, result_);
    if (small) {
      ScheduleResult better_one;
      const RouteCost bound = result_.cost;
      bool proven = false;
      if (solve_exact(working_, false, &bound, better_one, &proven)) {
        result_ = better_one;
      } else {
        result_.exact = proven;
      }
    }
  }
  // Report against the real deadlines (they differ from the working ones for kNoTimeWindows).
  StaticVector<std::uint8_t, kMaxStops> order = result_.order;
  const bool exact = result_.exact;
  finish(problem, {order.begin(), order.end()}, result_);
  result_.exact = exact;
  result_.bound = lower_bound(problem);
  const bool same =
      !warm.empty() && std::equal(order.begin(), order.end(), warm.begin(), warm.end());
  age_steps_ = same ? age_steps_ + 1 : 0;
  result_.age_steps = age_steps_;
  return result_;
}

// --- exact -------------------------------------------------------------------------------------

bool Scheduler::solve_exact(const ScheduleProblem& p, bool hard, const RouteCost* bound,
                            ScheduleResult& out, bool* proven) {
  const int n = p.n;
  const std::uint32_t full = (1U << n) - 1U;
  std::size_t used = 0;
  bool truncated = false;
  if (proven != nullptr) *proven = false;
  Label front[kFront];
  // Lower bounds for pruning against `bound`: stop j is reached from some other stop, so no
  // sooner than the quickest leg into it, and that leg is still to be travelled.
  std::array<double, kMaxStops + 1> min_in{};
  for (int j = 1; j <= n; ++j) {
    min_in[j] = n == 1 ? p.travel[0][j] : kInf;
    for (int i = 1; i <= n; ++i) {
      if (i != j) min_in[j] = std::min(min_in[j], p.travel[i][j]);
    }
  }
  const auto hopeless = [&](std::uint32_t mask, const Label& c) {
    if (bound == nullptr) return false;
    double late = c.lateness, travel = c.travel;
    for (int j = 1; j <= n; ++j) {
      if (mask & (1U << (j - 1))) continue;
      late += p.weight[j] * std::max(0.0, std::max(p.ready[j], c.arrival + min_in[j]) - p.due[j]);
      travel += min_in[j];
    }
    if (late > bound->lateness_s + kEps) return true;
    return late >= bound->lateness_s - kEps && travel >= bound->travel_s - kEps;
  };
  for (std::uint32_t mask = 1; mask <= full; ++mask) {
    for (int last = 0; last < n; ++last) {
      if ((mask & (1U << last)) == 0) continue;
      const auto node = static_cast<std::uint8_t>(last + 1);
      std::size_t count = 0;
      const auto offer = [&](const Label& c) {
        if ((hard && c.lateness > kEps) || hopeless(mask, c)) return;
        for (std::size_t i = 0; i < count; ++i) {
          const Label& e = front[i];
          if (e.lateness <= c.lateness + kEps && e.arrival <= c.arrival + kEps &&
              e.travel <= c.travel + kEps)
            return;
        }
        std::size_t keep = 0;
        for (std::size_t i = 0; i < count; ++i) {
          const Label& e = front[i];
          const bool dominated = c.lateness <= e.lateness + kEps && c.arrival <= e.arrival + kEps &&
                                 c.travel <= e.travel + kEps;
          if (!dominated) front[keep++] = e;
        }
        count = keep;
        if (count == kFront) {
          truncated = true;  // keep the lexicographically better of the candidate and the worst
          std::size_t worst = 0;
          for (std::size_t i = 1; i < count; ++i) {
            if (front[i].lateness > front[worst].lateness ||
                (front[i].lateness == front[worst].lateness &&
                 front[i].travel > front[worst].travel)) {
              worst = i;
            }
          }
          if (c.lateness < front[worst].lateness ||
              (c.lateness == front[worst].lateness && c.travel < front[worst].travel)) {
            front[worst] = c;
          }
          return;
        }
        front[count++] = c;
      };
      const std::uint32_t prev_mask = mask ^ (1U << last);
      if (prev_mask == 0) {
        const double a = std::max(p.ready[node], p.travel[0][node]);
        offer({p.weight[node] * std::max(0.0, a - p.due[node]), a, p.travel[0][node], kNone, node});
      } else {
        for (int prev = 0; prev < n; ++prev) {
          if ((prev_mask & (1U << prev)) == 0) continue;
          const std::size_t ps =
              static_cast<std::size_t>(prev_mask) * kExactMaxStops + static_cast<std::size_t>(prev);
          const double leg = p.travel[prev + 1][node];
          for (std::uint32_t i = state_begin_[ps]; i < state_begin_[ps] + state_count_[ps]; ++i) {
            const Label& l = pool_[i];
            const double a = std::max(p.ready[node], l.arrival + leg);
            offer({l.lateness + p.weight[node] * std::max(0.0, a - p.due[node]), a, l.travel + leg,
                   i, node});
          }
        }
      }
      if (used + count > kPool) return false;  // out of label memory: not proven
      const std::size_t st =
          static_cast<std::size_t>(mask) * kExactMaxStops + static_cast<std::size_t>(last);
      state_begin_[st] = static_cast<std::uint32_t>(used);
      state_count_[st] = static_cast<std::uint8_t>(count);
      std::copy_n(front, count, pool_.begin() + static_cast<std::ptrdiff_t>(used));
      used += count;
    }
  }
  // Best complete route (plus the way home for closed routes).
  std::uint32_t best = kNone;
  RouteCost best_cost{kInf, kInf, 0.0, false};
  for (int last = 0; last < n; ++last) {
    const std::size_t st =
        static_cast<std::size_t>(full) * kExactMaxStops + static_cast<std::size_t>(last);
    for (std::uint32_t i = state_begin_[st]; i < state_begin_[st] + state_count_[st]; ++i) {
      const Label& l = pool_[i];
      RouteCost c{l.lateness, l.travel, 0.0, true};
      if (p.closed) {
        const double home = p.travel[l.node][0];
        const double late = p.weight[0] * std::max(0.0, l.arrival + home - p.due[0]);
        if (hard && late > kEps) continue;
        c.lateness_s += late;
        c.travel_s += home;
      }
      if (best == kNone || better(c, best_cost)) {
        best = i;
        best_cost = c;
      }
    }
  }
  // Nothing found: with hard deadlines no order meets them all; against a bound, nothing beats
  // it, which proves the bound optimal unless a front had to be cut.
  if (proven != nullptr) *proven = best == kNone && !truncated;
  if (best == kNone) return false;
  StaticVector<std::uint8_t, kMaxStops> reversed;
  for (std::uint32_t i = best; i != kNone; i = pool_[i].parent)
    (void)reversed.push_back(pool_[i].node);
  StaticVector<std::uint8_t, kMaxStops> order;
  for (std::size_t i = reversed.size(); i-- > 0;)
    (void)order.push_back(reversed[i]);
  finish(p, {order.begin(), order.end()}, out);
  out.exact = !truncated;
  return true;
}

// --- heuristic -----------------------------------------------------------------------------------

namespace {

// Service start of every position of `route` (position 0 = node 0 at time 0) and the forward
// time slack: how much the start at a position may be delayed without making any later stop
// late. Returns false if the route is already late somewhere.
bool timing(const ScheduleProblem& p, std::span<const std::uint8_t> route, double* start,
            double* slack) {
  const std::size_t m = route.size();
  const auto node = [&](std::size_t pos) { return pos == 0 ? std::uint8_t{0} : route[pos - 1]; };
  start[0] = 0.0;
  for (std::size_t k = 1; k <= m; ++k)
    start[k] = std::max(p.ready[node(k)], start[k - 1] + p.travel[node(k - 1)][node(k)]);
  double f = p.closed ? p.due[0] - (start[m] + p.travel[node(m)][0]) : kInf;
  slack[m + 1] = kInf;
  for (std::size_t k = m; k >= 1; --k) {
    f = std::min(p.due[node(k)] - start[k], f);
    slack[k] = f;
    if (f < -kEps) return false;
    const double wait = start[k] - (start[k - 1] + p.travel[node(k - 1)][node(k)]);
    f += wait;  // delay at k-1 is first absorbed by the waiting at k
  }
  return true;
}

}  // namespace

void Scheduler::insertion(const ScheduleProblem& p, std::span<const std::uint8_t> stops) {
  for (const std::uint8_t u : stops) {
    const std::size_t m = route_.size();
    const bool feasible = timing(p, {route_.begin(), route_.end()}, start_.data(), slack_.data());
    std::size_t best_pos = m;
    double best_delta = kInf;
    if (feasible) {
      for (std::size_t q = 0; q <= m; ++q) {  // insert after position q
        const std::uint8_t a = q == 0 ? 0 : route_[q - 1];
        const double s = std::max(p.ready[u], start_[q] + p.travel[a][u]);
        if (s > p.due[u] + kEps) continue;
        double delta = p.travel[a][u];
        if (q < m) {
          const std::uint8_t b = route_[q];
          const double push = std::max(p.ready[b], s + p.travel[u][b]) - start_[q + 1];
          if (push > slack_[q + 1] + kEps) continue;
          delta += p.travel[u][b] - p.travel[a][b];
        } else if (p.closed) {
          if (s + p.travel[u][0] > p.due[0] + kEps) continue;
          delta += p.travel[u][0] - p.travel[a][0];
        }
        if (delta < best_delta) {
          best_delta = delta;
          best_pos = q;
        }
      }
    }
    if (best_delta == kInf) {  // no feasible place: the one that adds the least lateness
      RouteCost best_cost{kInf, kInf, 0.0, false};
      for (std::size_t q = 0; q <= m; ++q) {
        candidate_ = route_;
        (void)candidate_.push_back(u);
        std::rotate(candidate_.begin() + static_cast<std::ptrdiff_t>(q), candidate_.end() - 1,
                    candidate_.end());
        const RouteCost c = cost(p, {candidate_.begin(), candidate_.end()});
        if (best_cost.lateness_s == kInf || better(c, best_cost)) {
          best_cost = c;
          best_pos = q;
        }
      }
    }
    (void)route_.push_back(u);
    std::rotate(route_.begin() + static_cast<std::ptrdiff_t>(best_pos), route_.end() - 1,
                route_.end());
  }
}

// Or-opt: move a segment of 1-3 consecutive stops elsewhere; applies the first
// move that improves (lateness, travel) and returns true, false at a local optimum.
bool Scheduler::or_opt(const ScheduleProblem& p) {
  const std::size_t m = route_.size();
  const RouteCost current = cost(p, {route_.begin(), route_.end()});
  // The route's own timing, for moves on a route that is late somewhere: a move changes the
  // starts from its first moved position on, and only until they fall back onto the old ones.
  std::array<double, kMaxStops + 2> old_start{}, old_late{};
  if (!current.feasible) {
    std::uint8_t prev = 0;
    for (std::size_t k = 1; k <= m; ++k) {
      const std::uint8_t u = route_[k - 1];
      old_start[k] = std::max(p.ready[u], old_start[k - 1] + p.travel[prev][u]);
      old_late[k] = p.weight[u] * std::max(0.0, old_start[k] - p.due[u]);
      prev = u;
    }
    work_ += m;
  }
  for (std::size_t len = 1; len <= 3 && len < m; ++len) {
    for (std::size_t from = 0; from + len <= m; ++from) {
      if (work_ >= config_.work_budget) return false;  // out of time: this pass ends here
      // The route without the segment.
      candidate_.clear();
      for (std::size_t i = 0; i < m; ++i) {
        if (i < from || i >= from + len) (void)candidate_.push_back(route_[i]);
      }
      const std::span<const std::uint8_t> seg(route_.begin() + static_cast<std::ptrdiff_t>(from),
                                              len);
      const std::size_t r = candidate_.size();
      work_ += r + 1;
      const bool fast = current.feasible && timing(p, {candidate_.begin(), candidate_.end()},
                                                   start_.data(), slack_.data());
      const std::uint8_t before = from == 0 ? 0 : route_[from - 1];
      const std::uint8_t after = from + len < m ? route_[from + len] : 0;
      double internal = 0.0;
      for (std::size_t i = 1; i < len; ++i)
        internal += p.travel[seg[i - 1]][seg[i]];
      double removal = -(p.travel[before][seg[0]] + internal);
      if (from + len < m) {
        removal += p.travel[before][after] - p.travel[seg[len - 1]][after];
      } else if (p.closed) {
        removal += p.travel[before][0] - p.travel[seg[len - 1]][0];
      }
      for (std::size_t q = 0; q <= r; ++q) {
        if (q == from) continue;  // its own place
        // A late route is repaired by moving stops a short way; the long moves were most of the
        // work there (measured on the Dumas n = 60 set: 8 -> 11 of 25 feasible in one step).
        if (!current.feasible && (q > from + kRepairReach || from > q + kRepairReach)) continue;
        ++work_;
        const std::uint8_t a0 = q == 0 ? 0 : candidate_[q - 1];
        double delta = removal + internal + p.travel[a0][seg[0]];
        if (q < r) {
          const std::uint8_t b = candidate_[q];
          delta += p.travel[seg[len - 1]][b] - p.travel[a0][b];
        } else if (p.closed) {
          delta += p.travel[seg[len - 1]][0] - p.travel[a0][0];
        }
        if (fast) {
          // O(1): start times through the segment, then the push on the rest of the route.
          std::uint8_t a = a0;
          double s = start_[q];
          bool ok = true;
          for (const std::uint8_t u : seg) {
            s = std::max(p.ready[u], s + p.travel[a][u]);
            ok = ok && s <= p.due[u] + kEps;
            a = u;
          }
          if (!ok) continue;
          if (q < r) {
            const std::uint8_t b = candidate_[q];
            if (std::max(p.ready[b], s + p.travel[a][b]) - start_[q + 1] > slack_[q + 1] + kEps)
              continue;
          } else if (p.closed) {
            if (s + p.travel[a][0] > p.due[0] + kEps) continue;
          }
          if (delta >= -1e-7) continue;
        } else if (!current.feasible) {
          // Lateness of the moved route from its first changed position until its starts meet
          // the old ones again (from there on nothing changes).
          const std::size_t lo = std::min(from, q);
          const std::size_t hi = std::max(from, q) + len - 1;
          const auto node_at = [&](std::size_t i) {
            if (i < q) return candidate_[i];
            if (i < q + len) return seg[i - q];
            return candidate_[i - len];
          };
          double t = old_start[lo];
          std::uint8_t prev = lo == 0 ? 0 : route_[lo - 1];
          double late = 0.0;
          std::size_t i = lo;
          for (; i < m; ++i) {
            const std::uint8_t u = node_at(i);
            t = std::max(p.ready[u], t + p.travel[prev][u]);
            late += p.weight[u] * std::max(0.0, t - p.due[u]) - old_late[i + 1];
            prev = u;
            if (i > hi && std::abs(t - old_start[i + 1]) <= kEps) break;
          }
          work_ += i - lo + 1;
          if (i == m && p.closed) {
            const double old_home = old_start[m] + p.travel[route_[m - 1]][0];
            late += p.weight[0] * (std::max(0.0, t + p.travel[prev][0] - p.due[0]) -
                                   std::max(0.0, old_home - p.due[0]));
          }
          const RouteCost moved_cost{current.lateness_s + late, current.travel_s + delta, 0.0,
                                     false};
          if (!better(moved_cost, current)) continue;
        }
        StaticVector<std::uint8_t, kMaxStops> moved;
        for (std::size_t i = 0; i <= r; ++i) {
          if (i == q) {
            for (const std::uint8_t u : seg)
              (void)moved.push_back(u);
          }
          if (i < r) (void)moved.push_back(candidate_[i]);
        }
        if (better(cost(p, {moved.begin(), moved.end()}), current)) {
          route_ = moved;
          return true;
        }
      }
    }
  }
  return false;
}

// 2-opt: reverse a stretch of the route; applies the first improving reversal.
bool Scheduler::two_opt(const ScheduleProblem& p) {
  const std::size_t m = route_.size();
  const RouteCost current = cost(p, {route_.begin(), route_.end()});
  for (std::size_t i = 0; i + 1 < m && work_ < config_.work_budget; ++i) {
    for (std::size_t j = i + 1; j < m; ++j) {
      candidate_ = route_;
      std::reverse(candidate_.begin() + static_cast<std::ptrdiff_t>(i),
                   candidate_.begin() + static_cast<std::ptrdiff_t>(j) + 1);
      if (better(cost(p, {candidate_.begin(), candidate_.end()}), current)) {
        route_ = candidate_;
        return true;
      }
    }
  }
  return false;
}

void Scheduler::local_search(const ScheduleProblem& p) {
  while (work_ < config_.work_budget && (or_opt(p) || two_opt(p))) {
  }
}

void Scheduler::solve_heuristic(const ScheduleProblem& p, bool iterate,
                                std::span<const std::uint8_t> warm, ScheduleResult& out) {
  StaticVector<std::uint8_t, kMaxStops> order;
  for (int k = 1; k <= p.n; ++k)
    (void)order.push_back(static_cast<std::uint8_t>(k));
  const auto keep_if_better = [&](RouteCost& best_cost) {
    const RouteCost c = cost(p, {route_.begin(), route_.end()});
    if (best_.empty() || better(c, best_cost)) {
      best_ = route_;
      best_cost = c;
      return true;
    }
    return false;
  };
  RouteCost best_cost{};
  best_.clear();
  std::sort(order.begin(), order.end(), [&](std::uint8_t a, std::uint8_t b) {
    return p.due[a] != p.due[b] ? p.due[a] < p.due[b] : a < b;
  });
  if (!warm.empty()) {
    // The last plan: its live stops in its order, then the new ones inserted by deadline, each
    // where it costs least (an urgent new request goes to the front at once if it must).
    std::array<bool, kMaxStops + 1> seen{};
    route_.clear();
    for (const std::uint8_t k : warm) {
      if (k >= 1 && k <= p.n && !seen[k]) {
        seen[k] = true;
        (void)route_.push_back(k);
      }
    }
    candidate_.clear();
    for (const std::uint8_t k : order) {
      if (!seen[k]) (void)candidate_.push_back(k);
    }
    const StaticVector<std::uint8_t, kMaxStops> missing = candidate_;
    insertion(p, {missing.begin(), missing.end()});
    local_search(p);
    keep_if_better(best_cost);
  } else {
    rng_ = Rng(config_.seed + static_cast<std::uint64_t>(p.n));
  }
  // Constructions (a warm plan that meets every deadline needs none, and a warm step builds
  // them only with work left): insertion by deadline, then by distance from the UAV.
  const bool construct = warm.empty() || (!best_cost.feasible && work_ < config_.work_budget);
  if (construct) {
    route_.clear();
    insertion(p, {order.begin(), order.end()});
    local_search(p);
    keep_if_better(best_cost);
  }
  if (!iterate) {
    finish(p, {best_.begin(), best_.end()}, out);
    out.exact = false;
    return;
  }
  if (construct && (warm.empty() || work_ < config_.work_budget)) {
    std::sort(order.begin(), order.end(), [&](std::uint8_t a, std::uint8_t b) {
      return p.travel[0][a] != p.travel[0][b] ? p.travel[0][a] < p.travel[0][b] : a < b;
    });
    route_.clear();
    insertion(p, {order.begin(), order.end()});
    local_search(p);
    keep_if_better(best_cost);
  }
  // Iterated local search: perturb the best route (move a random stretch to a random place,
  // reverse another), descend again, keep improvements. Seeded: the same problem, the same
  // answer; a warm start continues the last solve's sequence instead of repeating it.
  Rng& rng = rng_;
  const std::size_t m = best_.size();
  const int patience = config_.stagnation_per_stop * p.n;
  for (int idle = 0; m >= 4 && work_ < config_.work_budget && idle < patience; ++idle) {
    route_ = best_;
    const std::size_t len = 1 + rng.below(std::min<std::size_t>(3, m - 1));
    const std::size_t from = rng.below(m - len + 1);
    candidate_.clear();
    for (std::size_t i = 0; i < m; ++i) {
      if (i < from || i >= from + len) (void)candidate_.push_back(route_[i]);
    }
    const std::size_t to = rng.below(candidate_.size() + 1);
    route_.clear();
    for (std::size_t i = 0; i <= candidate_.size(); ++i) {
      if (i == to) {
        for (std::size_t k = from; k < from + len; ++k)
          (void)route_.push_back(best_[k]);
      }
      if (i < candidate_.size()) (void)route_.push_back(candidate_[i]);
    }
    const std::size_t a = rng.below(m - 1), b = a + 1 + rng.below(m - a - 1);
    std::reverse(route_.begin() + static_cast<std::ptrdiff_t>(a),
                 route_.begin() + static_cast<std::ptrdiff_t>(b) + 1);
    local_search(p);
    if (keep_if_better(best_cost)) idle = -1;
  }
  finish(p, {best_.begin(), best_.end()}, out);
  out.exact = false;
}

}  // namespace colag::uav
