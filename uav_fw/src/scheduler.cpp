#include "colag/uav/scheduler.hpp"

#include "colag/common/random.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colag::uav {

namespace {
constexpr double kEps = 1e-9;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGain = 1e-7;             // a move must shorten the route by more than this
constexpr std::size_t kRepairReach = 10;   // positions a stop moves on a route that is late
constexpr std::size_t kPerturbMoves = 3;   // the search's kick: up to 3 stretches moved,
constexpr std::size_t kPerturbReach = 15;  // each up to 15 positions,
constexpr std::uint64_t kGlobalKick = 4;   // or anywhere, one kick in 4
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
    last_order_.clear();
    last_search_.clear();
    return result_;
  }
  if (config_.mode == ScheduleMode::kNoTimeWindows) {
    for (int k = 0; k <= n; ++k)
      working_.due[k] = kInf;
  }
  const bool small = n <= std::min(config_.exact_max_stops, kExactMaxStops);
  bool searched = false;
  // The exact solver first looks for the shortest order that meets every deadline, unless a
  // stop is late even on the quickest path to it: then none does (a UGV already stopped for
  // support has its deadline now, so this is most solves in a crowd: 2233 of 2238 with 16 UGVs,
  // and that first pass was 40 % of the scheduler's time).
  if (!small || !lower_bound(working_).feasible || !solve_exact(working_, true, nullptr, result_)) {
    // No order meets every deadline (or too many stops for the exact solver): the heuristic
    // gives an incumbent; the exact solver, pruning against it, either beats it or proves it.
    solve_heuristic(working_, !small, warm, result_);
    searched = true;
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
  last_order_ = order;
  if (!searched) last_search_.clear();  // only a heuristic solve leaves a search to resume
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
          for (std::uint32_t i = labels_.first(ps); i < labels_.end(ps); ++i) {
            const Label& l = labels_.pool[i];
            const double a = std::max(p.ready[node], l.arrival + leg);
            offer({l.lateness + p.weight[node] * std::max(0.0, a - p.due[node]), a, l.travel + leg,
                   i, node});
          }
        }
      }
      if (used + count > ExactLabels::kPool) return false;  // out of label memory: not proven
      const std::size_t st =
          static_cast<std::size_t>(mask) * kExactMaxStops + static_cast<std::size_t>(last);
      labels_.state_begin[st] = static_cast<std::uint32_t>(used);
      labels_.state_count[st] = static_cast<std::uint8_t>(count);
      std::copy_n(front, count, labels_.pool.begin() + static_cast<std::ptrdiff_t>(used));
      used += count;
    }
  }
  // Best complete route (plus the way home for closed routes).
  std::uint32_t best = kNone;
  RouteCost best_cost{kInf, kInf, 0.0, false};
  for (int last = 0; last < n; ++last) {
    const std::size_t st =
        static_cast<std::size_t>(full) * kExactMaxStops + static_cast<std::size_t>(last);
    for (std::uint32_t i = labels_.first(st); i < labels_.end(st); ++i) {
      const Label& l = labels_.pool[i];
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
  for (std::uint32_t i = best; i != kNone; i = labels_.pool[i].parent)
    (void)reversed.push_back(labels_.pool[i].node);
  StaticVector<std::uint8_t, kMaxStops> order;
  for (std::size_t i = reversed.size(); i-- > 0;)
    (void)order.push_back(reversed[i]);
  finish(p, {order.begin(), order.end()}, out);
  out.exact = !truncated;
  return true;
}

bool Scheduler::subset_costs(const ScheduleProblem& p, std::span<RouteCost> costs) {
  const int n = p.n;
  if (n < 0 || n > kExactMaxStops || p.closed || costs.size() < (std::size_t{1} << n)) return false;
  costs[0] = RouteCost{};
  if (n == 0) return true;
  ScheduleResult full;
  if (!solve_exact(p, false, nullptr, full)) return false;
  for (std::uint32_t mask = 1; mask < (1U << n); ++mask) {
    RouteCost best{kInf, kInf, 0.0, false};
    for (int last = 0; last < n; ++last) {
      if ((mask & (1U << last)) == 0) continue;
      const std::size_t st =
          static_cast<std::size_t>(mask) * kExactMaxStops + static_cast<std::size_t>(last);
      for (std::uint32_t i = labels_.first(st); i < labels_.end(st); ++i) {
        const RouteCost c{labels_.pool[i].lateness, labels_.pool[i].travel, 0.0,
                          labels_.pool[i].lateness <= kEps};
        if (better(c, best)) best = c;
      }
    }
    costs[mask] = best;
  }
  return full.exact;
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

// --- moves on (time warp, travel) -----------------------------------------------------------

Scheduler::Piece Scheduler::stop(const ScheduleProblem& p, std::uint8_t u) {
  Piece s;
  s.early = p.ready[u];
  s.late = p.due[u];
  s.first = s.last = u;
  s.empty = false;
  return s;
}

Scheduler::Piece Scheduler::join(const ScheduleProblem& p, const Piece& a, const Piece& b) {
  if (a.empty) return b;
  if (b.empty) return a;
  const double leg = p.travel[a.last][b.first];
  const double shift = a.duration - a.warp + leg;
  const double wait = std::max(b.early - shift - a.late, 0.0);
  const double warp = std::max(a.early + shift - b.late, 0.0);
  Piece s;
  s.duration = a.duration + b.duration + leg + wait;
  s.warp = a.warp + b.warp + warp;
  s.early = std::max(b.early - shift, a.early) - wait;
  s.late = std::min(b.late - shift, a.late) + warp;
  s.travel = a.travel + b.travel + leg;
  s.first = a.first;
  s.last = b.last;
  s.empty = false;
  return s;
}

Scheduler::Piece Scheduler::whole(const ScheduleProblem& p) {
  pieces(p);
  return join(p, prefix_[0], suffix_[0]);
}

bool Scheduler::improves(const Piece& now, const Piece& moved) {
  return moved.warp < now.warp - kEps ||
         (moved.warp <= now.warp + kEps && moved.travel < now.travel - kGain);
}

int Scheduler::after(const ScheduleProblem& p, std::size_t k) const {
  return k < route_.size() ? int{route_[k]} : (p.closed ? 0 : -1);
}

void Scheduler::move_stretch(std::size_t from, std::size_t len, std::size_t to) {
  const auto at = [&](std::size_t i) { return route_.begin() + static_cast<std::ptrdiff_t>(i); };
  if (to < from) std::rotate(at(to), at(from), at(from + len));
  if (to > from) std::rotate(at(from), at(from + len), at(to + len));
}

void Scheduler::pieces(const ScheduleProblem& p) {
  const std::size_t m = route_.size();
  Piece start = stop(p, 0);
  start.early = start.late = 0.0;  // the route leaves node 0 now
  prefix_[0] = start;
  for (std::size_t k = 0; k < m; ++k)
    prefix_[k + 1] = join(p, prefix_[k], stop(p, route_[k]));
  suffix_[m] = p.closed ? stop(p, 0) : Piece{};
  for (std::size_t k = m; k-- > 0;)
    suffix_[k] = join(p, stop(p, route_[k]), suffix_[k + 1]);
  work_ += 6 * m;
}

// A move is taken if it lowers the time warp, or keeps it and shortens the route. On a route
// that is on time, a move's travel is known from its legs alone, and only a shorter route needs
// its timing checked. Time warp only grows as pieces are joined, so a piece already over the
// route's warp ends a scan. Work: a unit per candidate, 3 per join.
bool Scheduler::or_opt_on_time(const ScheduleProblem& p) {
  const std::size_t m = route_.size();
  const Piece now = whole(p);
  const bool late = now.warp > kEps;
  const auto next = [&](std::size_t k) { return after(p, k); };
  const auto leg = [&](int a, int b) { return b < 0 ? 0.0 : p.travel[a][b]; };
  // Each scan starts where the last move was found (moves nearby are the likely next ones) and
  // looks only at stretches starting at a stop whose neighbourhood changed since it was last
  // looked at ("don't look bits"): after a small kick, a few.
  const auto mark = [&](std::size_t pos) {
    if (pos < m) look_[route_[pos]] = true;
  };
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t from = (scan_ + k) % m;
    if (!look_[route_[from]]) continue;
    for (std::size_t len = 1; len <= 3 && len < m && from + len <= m; ++len) {
      if (work_ >= config_.work_budget) return false;
      Piece seg;
      for (std::size_t i = from; i < from + len; ++i)
        seg = join(p, seg, stop(p, route_[i]));
      work_ += 3 * len;
      const int s0 = route_[from], s1 = route_[from + len - 1];
      const int before = from == 0 ? 0 : route_[from - 1], after = next(from + len);
      const double out = leg(before, after) - p.travel[before][s0] - leg(s1, after);
      // Later: before | the stops after the segment up to `to` | segment | the rest.
      // A late route is repaired by moving stops a short way (see kRepairReach).
      const std::size_t reach = late ? kRepairReach : m;
      // The pieces grow lazily: only a candidate worth checking pays for its joins.
      Piece head = prefix_[from];
      std::size_t head_end = from + len;  // head = route up to here, without the segment
      for (std::size_t to = from + len; to < m && to < from + len + reach; ++to) {
        ++work_;
        const int t = route_[to], u = next(to + 1);
        const double delta = out + p.travel[t][s0] + leg(s1, u) - leg(t, u);
        if (!late && delta >= -kGain) continue;
        for (; head_end <= to; ++head_end, work_ += 3)
          head = join(p, head, stop(p, route_[head_end]));
        if (head.warp > now.warp + kEps) break;
        work_ += 6;
        if (improves(now, join(p, join(p, head, seg), suffix_[to + 1]))) {
          for (const std::size_t pos : {from - 1, from, from + len, to, to + 1})
            mark(pos);
          move_stretch(from, len, to + 1 - len);
          scan_ = from;
          return true;
        }
      }
      // Earlier: before `to` | segment | the stops from `to` up to the segment | the rest.
      Piece mid;
      std::size_t mid_begin = from;  // mid = the route from here up to the segment
      for (std::size_t to = from; to-- > 0 && to + reach >= from;) {
        ++work_;
        const int t = route_[to], b = to == 0 ? 0 : route_[to - 1];
        const double delta = out + p.travel[b][s0] + p.travel[s1][t] - p.travel[b][t];
        if (!late && delta >= -kGain) continue;
        for (; mid_begin > to; work_ += 3)
          mid = join(p, stop(p, route_[--mid_begin]), mid);
        if (mid.warp > now.warp + kEps) break;
        work_ += 9;
        if (improves(now, join(p, join(p, join(p, prefix_[to], seg), mid), suffix_[from + len]))) {
          for (const std::size_t pos : {to - 1, to, from - 1, from, from + len})
            mark(pos);
          move_stretch(from, len, to);
          scan_ = to;
          return true;
        }
      }
    }
    look_[route_[from]] = false;  // nothing to gain here until a neighbour moves
  }
  return false;
}

bool Scheduler::two_opt_on_time(const ScheduleProblem& p) {
  const std::size_t m = route_.size();
  const Piece now = whole(p);
  const bool late = now.warp > kEps;
  for (std::size_t i = 0; i + 1 < m && work_ < config_.work_budget; ++i) {
    Piece reversed = stop(p, route_[i]);
    std::size_t reversed_end = i + 1;  // reversed = the route from i up to here, backwards
    const int a = i == 0 ? 0 : route_[i - 1];
    double forward = 0.0, backward = 0.0;  // the stretch's inner legs, each way
    for (std::size_t j = i + 1; j < m; ++j) {
      ++work_;
      forward += p.travel[route_[j - 1]][route_[j]];
      backward += p.travel[route_[j]][route_[j - 1]];
      const int b = after(p, j + 1);
      const double delta = p.travel[a][route_[j]] - p.travel[a][route_[i]] + backward - forward +
                           (b < 0 ? 0.0 : p.travel[route_[i]][b] - p.travel[route_[j]][b]);
      if (!late && delta >= -kGain) continue;
      for (; reversed_end <= j; ++reversed_end, work_ += 3)
        reversed = join(p, stop(p, route_[reversed_end]), reversed);
      if (reversed.warp > now.warp + kEps) break;  // a longer reversal only adds to it
      work_ += 6;
      if (improves(now, join(p, join(p, prefix_[i], reversed), suffix_[j + 1]))) {
        std::reverse(route_.begin() + static_cast<std::ptrdiff_t>(i),
                     route_.begin() + static_cast<std::ptrdiff_t>(j) + 1);
        return true;
      }
    }
  }
  return false;
}

// --- moves on a route that is late: on its real objective ---------------------------------

// Or-opt on (lateness, travel): moves a stretch of 1-3 stops at most kRepairReach positions.
// A move changes the starts from its first moved position on, and only until they fall back
// onto the old ones: only that part is walked.
bool Scheduler::or_opt_late(const ScheduleProblem& p) {
  const std::size_t m = route_.size();
  const RouteCost current = cost(p, {route_.begin(), route_.end()});
  std::array<double, kMaxStops + 2> old_start{}, old_late{};
  std::uint8_t last = 0;
  for (std::size_t k = 1; k <= m; ++k) {
    const std::uint8_t u = route_[k - 1];
    old_start[k] = std::max(p.ready[u], old_start[k - 1] + p.travel[last][u]);
    old_late[k] = p.weight[u] * std::max(0.0, old_start[k] - p.due[u]);
    last = u;
  }
  const auto next = [&](std::size_t k) { return after(p, k); };
  const auto leg = [&](int a, int b) { return b < 0 ? 0.0 : p.travel[a][b]; };
  for (std::size_t len = 1; len <= 3 && len < m; ++len) {
    for (std::size_t from = 0; from + len <= m; ++from) {
      if (work_ >= config_.work_budget) return false;
      const int s0 = route_[from], s1 = route_[from + len - 1];
      const int before = from == 0 ? 0 : route_[from - 1], after = next(from + len);
      const double out = leg(before, after) - p.travel[before][s0] - leg(s1, after);
      const std::size_t lo_to = from > kRepairReach ? from - kRepairReach : 0;
      const std::size_t hi_to = std::min(m - len, from + kRepairReach);
      for (std::size_t to = lo_to; to <= hi_to; ++to) {  // the segment's new first position
        if (to == from) continue;
        // The moved route, position by position, and its travel from the changed legs.
        const auto node_at = [&](std::size_t i) -> std::uint8_t {
          if (i < to || i >= to + len) {
            const std::size_t j = i < std::min(from, to) || i >= std::max(from, to) + len ? i
                                  : to < from                                             ? i - len
                                                                                          : i + len;
            return route_[j];
          }
          return route_[from + (i - to)];
        };
        double delta = out;
        if (to > from) {
          const int t = route_[to + len - 1], u = next(to + len);
          delta += p.travel[t][s0] + leg(s1, u) - leg(t, u);
        } else {
          const int t = route_[to], b = to == 0 ? 0 : route_[to - 1];
          delta += p.travel[b][s0] + p.travel[s1][t] - p.travel[b][t];
        }
        const std::size_t lo = std::min(from, to), hi = std::max(from, to) + len - 1;
        double t = old_start[lo];
        int prev = lo == 0 ? 0 : route_[lo - 1];
        double late = 0.0;
        std::size_t i = lo;
        for (; i < m; ++i) {
          const std::uint8_t u = node_at(i);
          t = std::max(p.ready[u], t + p.travel[prev][u]);
          late += p.weight[u] * std::max(0.0, t - p.due[u]) - old_late[i + 1];
          prev = u;
          if (i > hi && std::abs(t - old_start[i + 1]) <= kEps) break;
        }
        work_ += i - lo + 2;
        if (i == m && p.closed) {
          const double old_home = old_start[m] + p.travel[route_[m - 1]][0];
          late += p.weight[0] * (std::max(0.0, t + p.travel[prev][0] - p.due[0]) -
                                 std::max(0.0, old_home - p.due[0]));
        }
        if (!better({current.lateness_s + late, current.travel_s + delta, 0.0, false}, current))
          continue;
        move_stretch(from, len, to);
        return true;
      }
    }
  }
  return false;
}

void Scheduler::local_search(const ScheduleProblem& p, bool everywhere) {
  if (everywhere) look_.fill(true);
  while (work_ < config_.work_budget && (or_opt_on_time(p) || two_opt_on_time(p))) {
  }
}

void Scheduler::reduce_lateness(const ScheduleProblem& p) {
  while (work_ < config_.work_budget && or_opt_late(p)) {
  }
}

void Scheduler::solve_heuristic(const ScheduleProblem& p, bool iterate,
                                std::span<const std::uint8_t> warm, ScheduleResult& out) {
  StaticVector<std::uint8_t, kMaxStops> order;
  for (int k = 1; k <= p.n; ++k)
    (void)order.push_back(static_cast<std::uint8_t>(k));
  // Two incumbents: the best route by the objective (lateness, travel), which is returned, and
  // the one the search goes on from, best by (time warp, travel): lateness alone can hide the
  // way to a route on time (a route may be less late in total and yet further from on time).
  double search_warp = kInf, search_travel = kInf;
  double route_warp = 0.0, route_travel = 0.0;  // route_'s, as keep_if_better saw it
  const auto keep_if_better = [&](RouteCost& best_cost) {
    const RouteCost c = cost(p, {route_.begin(), route_.end()});
    const double warp = whole(p).warp;
    route_warp = warp;
    route_travel = c.travel_s;
    bool progress = false;
    if (warp < search_warp - kEps ||
        (warp <= search_warp + kEps && c.travel_s < search_travel - kGain)) {
      search_ = route_;
      search_warp = warp;
      search_travel = c.travel_s;
      progress = true;
    }
    if (best_.empty() || better(c, best_cost)) {
      best_ = route_;
      best_cost = c;
      progress = true;
    }
    return progress;
  };
  RouteCost best_cost{};
  best_.clear();
  search_.clear();
  std::sort(order.begin(), order.end(), [&](std::uint8_t a, std::uint8_t b) {
    return p.due[a] != p.due[b] ? p.due[a] < p.due[b] : a < b;
  });
  bool resumed = false;  // the search resumes the last solve's
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
    keep_if_better(best_cost);  // the search below may trade lateness for time warp
    // The plan this scheduler returned last time: its search goes on from where it was (the
    // route it was searching from need not be the plan, when no route is on time).
    resumed = std::equal(warm.begin(), warm.end(), last_order_.begin(), last_order_.end()) &&
              last_search_.size() == static_cast<std::size_t>(p.n);
    if (resumed) route_ = last_search_;
    local_search(p, true);
    keep_if_better(best_cost);
  } else {
    rng_ = Rng(config_.seed + static_cast<std::uint64_t>(p.n));
  }
  // Constructions: insertion by deadline, then by distance from the UAV. A warm start builds
  // them only when its plan is late and new (a resumed search has built them already).
  const bool construct =
      warm.empty() || (!best_cost.feasible && !resumed && work_ < config_.work_budget);
  if (construct) {
    route_.clear();
    insertion(p, {order.begin(), order.end()});
    local_search(p, true);
    keep_if_better(best_cost);
  }
  // No route on time: the best one descends on its real objective, its lateness.
  const auto polish = [&](RouteCost& best) {
    if (best.feasible) return;
    route_ = best_;
    reduce_lateness(p);
    keep_if_better(best);
  };
  if (!iterate) {
    polish(best_cost);
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
    local_search(p, true);
    keep_if_better(best_cost);
  }
  // Iterated local search: kick the search's route (move 1-3 short stretches, mostly a short
  // way: on routes with time windows a long move or a reversal is seldom on time), descend
  // again, keep improvements. After `patience` kicks without progress a cold solve ends; a warm
  // one (counting across steps) restarts from a new construction, by deadline with noise (some
  // problems have far apart basins that small kicks never cross), and ends at the next stall.
  // Seeded: the same problem, the same answer; a warm start continues the last solve's sequence
  // instead of repeating it.
  Rng& rng = rng_;
  const std::size_t m = best_.size();
  const int patience = std::max(1, config_.stagnation_per_stop * p.n);
  const auto mark = [&](std::size_t pos) {
    if (pos < m) look_[route_[pos]] = true;
  };
  // A quarter of the budget is kept for the lateness polish while no route is on time.
  const auto searching = [&] {
    return work_ < (best_cost.feasible ? config_.work_budget
                                       : config_.work_budget - config_.work_budget / 4);
  };
  if (warm.empty()) idle_ = 0;
  bool restarted = false;
  while (m >= 4 && searching()) {
    // A cold solve ends here (its answer is due now); a warm one restarts once per step, so a
    // settled plan costs a restart's work per step, not the whole budget.
    if (idle_ >= patience && (warm.empty() || restarted)) break;
    if (idle_ >= patience) {
      idle_ = 0;
      restarted = true;
      double first = kInf, last = -kInf;
      for (const std::uint8_t k : order) {
        first = std::min(first, p.due[k]);
        last = std::max(last, p.due[k]);
      }
      const double spread = last - first;
      const double noise = rng.uniform(0.05, 0.5) * (std::isfinite(spread) ? spread : 0.0);
      for (std::size_t k = 0; k < m; ++k)
        key_[order[k]] = p.due[order[k]] + rng.uniform(0.0, noise);
      std::sort(order.begin(), order.end(), [&](std::uint8_t a, std::uint8_t b) {
        return key_[a] != key_[b] ? key_[a] < key_[b] : a < b;
      });
      route_.clear();
      insertion(p, {order.begin(), order.end()});
      local_search(p, true);
      keep_if_better(best_cost);
      search_ = route_;  // the search goes on from here, better or not
      search_warp = route_warp;
      search_travel = route_travel;
      continue;
    }
    route_ = search_;
    look_.fill(false);
    const std::size_t reach = rng.below(kGlobalKick) == 0 ? m : kPerturbReach;
    const std::size_t moves = 1 + rng.below(kPerturbMoves);
    for (std::size_t k = 0; k < moves; ++k) {
      const std::size_t len = 1 + rng.below(std::min<std::size_t>(3, m - 1));
      const std::size_t from = rng.below(m - len + 1);
      const std::size_t lo = from > reach ? from - reach : 0;
      const std::size_t to = lo + rng.below(std::min(m - len, from + reach) - lo + 1);
      for (const std::size_t pos : {from - 1, from, from + len, to - 1, to, to + len})
        mark(pos);
      move_stretch(from, len, to);
      for (const std::size_t pos : {from - 1, from, from + len, to - 1, to, to + len})
        mark(pos);
    }
    local_search(p, false);
    idle_ = keep_if_better(best_cost) ? 0 : idle_ + 1;
  }
  polish(best_cost);
  finish(p, {best_.begin(), best_.end()}, out);
  out.exact = false;
  last_search_ = search_;
}

}  // namespace colag::uav
