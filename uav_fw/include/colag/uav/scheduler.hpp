#pragma once
// The UAV's support scheduling (paper Sec. III-D) as an open vehicle-routing problem with time
// windows for one vehicle: node 0 is the UAV, nodes 1..n the live support requests. A route
// visits every stop once; arriving before `ready` means waiting, after `due` means lateness.
// Objective, lexicographic: total lateness (sum of max(0, arrival - due), each stop's weighted
// by its `weight`, 1 unless set), then travel time.
// So when some order meets every deadline, the shortest such order wins (the paper's VRPTW);
// when none does, the order that makes the UGVs wait least in total (better than the paper's
// "raise v_max until feasible", which says nothing about which UGV waits).
// Solvers, both with static memory and bounded time:
// - exact, n <= kExactMaxStops: dynamic programming over subsets with Pareto labels
//   (lateness, arrival, travel) per (visited set, last stop); a first pass with hard deadlines
//   prunes every late state and usually settles it;
// - heuristic, any n <= kMaxStops: deadline-ordered feasible insertion with O(1) forward
//   time-slack checks (Savelsbergh), then local search (Or-opt relocation of 1-3 stops with
//   O(1) checks on time warp, 2-opt reversal) iterated from seeded perturbations within a fixed
//   work budget; a route that cannot be on time is then polished on its lateness.
// Anytime: given the last plan (`warm`), the heuristic starts from it (stops it does not hold
// inserted, stops no longer live dropped) and continues its search where the last step left
// it, so the plan improves across steps within each step's budget.
// Ablations: kNoTimeWindows (plain open TSP: deadlines ignored while solving), kNoScheduling
// (serve the smallest deadline first).
#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "colag/common/limits.hpp"
#include "colag/common/random.hpp"
#include "colag/common/static_vector.hpp"

namespace colag::uav {

inline constexpr std::size_t kMaxStops = limits::kMaxSupportRequests;
inline constexpr int kExactMaxStops = 12;

namespace detail {
constexpr std::array<double, kMaxStops + 1> ones() {
  std::array<double, kMaxStops + 1> a{};
  for (double& x : a)
    x = 1.0;
  return a;
}
}  // namespace detail

struct ScheduleProblem {
  int n = 0;                                                              // stops 1..n
  std::array<std::array<double, kMaxStops + 1>, kMaxStops + 1> travel{};  // seconds, i -> j
  std::array<double, kMaxStops + 1> ready{};
  std::array<double, kMaxStops + 1> due{};
  // What a second of lateness at each stop costs (> 0): the UAV weighs a UGV that has already
  // waited long more, so that a far one is not left for ever behind nearer, newer requests.
  std::array<double, kMaxStops + 1> weight = detail::ones();
  bool closed = false;  // the route ends back at node 0 (TSPTW benchmark instances)
};

enum class ScheduleMode : std::uint8_t { kTimeWindows, kNoTimeWindows, kNoScheduling };

struct RouteCost {
  double lateness_s = 0.0;  // weighted
  double travel_s = 0.0;
  double max_lateness_s = 0.0;  // not weighted
  bool feasible = true;
};

struct ScheduleResult {
  StaticVector<std::uint8_t, kMaxStops> order;  // stops in visiting order
  std::array<double, kMaxStops + 1> arrival{};  // service start per node
  RouteCost cost;
  RouteCost bound;     // no order does better than this (lateness, then travel, each a bound)
  bool exact = false;  // proven optimal for the objective
  std::uint32_t age_steps = 0;  // warm-started solves since the order last changed
};

// Evaluates `order` (stop numbers 1..n); fills arrivals if given.
RouteCost evaluate(const ScheduleProblem& p, std::span<const std::uint8_t> order,
                   double* arrival = nullptr);

struct SchedulerConfig {
  ScheduleMode mode = ScheduleMode::kTimeWindows;
  int exact_max_stops = kExactMaxStops;
  // Heuristic effort: route evaluations (one unit per stop looked at) across all restarts.
  // Bounds the solve time for any n: about 1 ms on a desktop core.
  std::uint64_t work_budget = 200'000;
  int stagnation_per_stop = 1;  // iterated search ends after n perturbations without progress
  std::uint64_t seed = 0x5eed;  // of the search's perturbations
};

// The exact solver's label memory (4 MB): scratch of one solve, nothing in it outlives the solve.
// The UAV's schedulers (its own and the fleet's) take turns in one loop and share one.
class ExactLabels {
 public:
  struct Label {
    double lateness, arrival, travel;
    std::uint32_t parent;  // index in pool, kNone for the first stop
    std::uint8_t node;
  };
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  static constexpr std::size_t kStates = (std::size_t{1} << kExactMaxStops) * kExactMaxStops;
  static constexpr std::size_t kPool = std::size_t{1} << 17;

  std::array<Label, kPool> pool;
  std::array<std::uint32_t, kStates> state_begin;  // per (visited set, last stop): its labels
  std::array<std::uint8_t, kStates> state_count;
  // State st's labels: pool[first(st)] up to pool[end(st)].
  std::uint32_t first(std::size_t st) const { return state_begin[st]; }
  std::uint32_t end(std::size_t st) const { return state_begin[st] + state_count[st]; }
};

class Scheduler {
 public:
  // `labels`: label memory shared with other schedulers of the same thread (never two solves at
  // once); without it the scheduler allocates its own here (tests, tools), never in solve().
  explicit Scheduler(const SchedulerConfig& config = {}, ExactLabels* labels = nullptr)
      : config_(config),
        own_(labels == nullptr ? std::make_unique<ExactLabels>() : nullptr),
        labels_(labels == nullptr ? *own_ : *labels) {}
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;
  // Returns the best order found; `result.exact` tells whether it is proven optimal. `warm`: the
  // last plan's order in this problem's stop numbers (entries out of range or repeated are
  // ignored): the search continues from it; without it, the same problem gives the same answer.
  const ScheduleResult& solve(const ScheduleProblem& problem,
                              std::span<const std::uint8_t> warm = {});
  const SchedulerConfig& config() const { return config_; }
  void set_work_budget(std::uint64_t work) { config_.work_budget = work; }  // from the next solve
  std::uint64_t last_work() const { return work_; }  // the last solve's heuristic work
  // Exact, open routes, n <= kExactMaxStops: the best route over every subset of the stops
  // (`costs[mask]`, bit j - 1 for stop j; costs[0] is the empty route): what a fleet needs to
  // split the stops among its vehicles (fleet_scheduler.hpp). `costs` holds 2^n entries. False
  // if some subset's optimum is not proven (a label front was cut, or label memory ran out).
  bool subset_costs(const ScheduleProblem& p, std::span<RouteCost> costs);

 private:
  using Label = ExactLabels::Label;
  static constexpr std::uint32_t kNone = ExactLabels::kNone;
  static constexpr std::size_t kFront = 32;

  // Exact DP. `hard` drops every late label; `bound` (optional) drops every label that cannot
  // beat it. Returns true with the optimum in `out` (`out.exact` false if a front overflowed),
  // false when nothing qualifies: then `*proven` says whether that is proven (bound optimal,
  // or no order meets the hard deadlines) or the label pool ran out.
  bool solve_exact(const ScheduleProblem& p, bool hard, const RouteCost* bound, ScheduleResult& out,
                   bool* proven = nullptr);
  // `iterate`: spend the work budget on iterated local search (when its answer is final);
  // otherwise one construction + descent (an incumbent for the exact solver to prune with).
  void solve_heuristic(const ScheduleProblem& p, bool iterate, std::span<const std::uint8_t> warm,
                       ScheduleResult& out);
  // Inserts `stops` one by one into route_, each where it costs least.
  void insertion(const ScheduleProblem& p, std::span<const std::uint8_t> stops);
  // Moves on (time warp, travel), each checked in O(1) by joining precomputed pieces of the
  // route (Vidal et al. 2013's concatenation of subsequences); each applies one improving move.
  bool or_opt_on_time(const ScheduleProblem& p);
  bool two_opt_on_time(const ScheduleProblem& p);
  void pieces(const ScheduleProblem& p);  // prefix_ and suffix_ of route_
  // Or-opt on the real objective (lateness, travel), for a route that cannot be on time.
  bool or_opt_late(const ScheduleProblem& p);
  void reduce_lateness(const ScheduleProblem& p);
  // Descends on (time warp, travel); `everywhere`: every stop looked at, else those marked.
  void local_search(const ScheduleProblem& p, bool everywhere);
  RouteCost cost(const ScheduleProblem& p, std::span<const std::uint8_t> order);  // counts work
  bool better(const RouteCost& a, const RouteCost& b) const;
  void finish(const ScheduleProblem& p, std::span<const std::uint8_t> order,
              ScheduleResult& out) const;

  SchedulerConfig config_;
  ScheduleProblem working_;  // the problem as solved (deadlines relaxed for kNoTimeWindows)
  ScheduleResult result_;
  std::unique_ptr<ExactLabels> own_;
  ExactLabels& labels_;
  // heuristic scratch
  StaticVector<std::uint8_t, kMaxStops> route_, candidate_, best_, search_;
  // The last solve's plan and the route its search went on from (warm starts resume from it).
  StaticVector<std::uint8_t, kMaxStops> last_order_, last_search_;
  std::uint64_t work_ = 0;
  std::array<double, kMaxStops + 2> start_{}, slack_{};
  // A stretch of stops flown in order: its duration, its earliest and latest feasible start,
  // the lateness it cannot avoid ("time warp": 0 when it can meet every deadline), its travel.
  struct Piece {
    double duration = 0, early = 0, late = 0, warp = 0, travel = 0;
    std::uint8_t first = 0, last = 0;
    bool empty = true;
  };
  static Piece join(const ScheduleProblem& p, const Piece& a, const Piece& b);
  static Piece stop(const ScheduleProblem& p, std::uint8_t u);
  Piece whole(const ScheduleProblem& p);  // pieces(), and route_ as one piece
  // A move is taken if it lowers the time warp, or keeps it and shortens the route.
  static bool improves(const Piece& now, const Piece& moved);
  int after(const ScheduleProblem& p, std::size_t k) const;  // node after position k; -1: none
  // Moves the stretch [from, from + len) of route_ so that it starts at position `to`.
  void move_stretch(std::size_t from, std::size_t len, std::size_t to);
  std::array<Piece, kMaxStops + 2> prefix_{}, suffix_{};
  std::size_t scan_ = 0;                     // where the next Or-opt scan starts
  std::array<bool, kMaxStops + 1> look_{};   // per stop: its stretches are worth a look
  std::array<double, kMaxStops + 1> key_{};  // a restart's construction order
  int idle_ = 0;                             // kicks without progress, across warm solves
  Rng rng_{0};                               // reseeded by a cold solve, continued by warm ones
  std::uint32_t age_steps_ = 0;
};

}  // namespace colag::uav
