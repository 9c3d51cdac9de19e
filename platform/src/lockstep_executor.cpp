#include "colag/platform/lockstep_executor.hpp"

namespace colag::platform {

namespace {
// Lanes are forked only when the steps released in them took this long on average so far:
// waking a worker costs more than a few short control steps.
constexpr Duration kWorthForking = std::chrono::microseconds(30);
}  // namespace

LockstepExecutor::LockstepExecutor(TimePoint start, const hal::Clock* stopwatch)
    : stopwatch_(stopwatch) {
  clock_.now_ = start;
}

void LockstepExecutor::run_row(std::size_t i, TimePoint t) {
  if (schedule_.release_of(i) != t) return;
  const TimePoint w0 = stopwatch_ ? stopwatch_->now() : TimePoint{};
  schedule_.entry(i).task->step(t);
  const Duration took = stopwatch_ ? stopwatch_->now() - w0 : Duration::zero();
  schedule_.complete(i, t, took, t);
}

Duration LockstepExecutor::mean_step(std::size_t i) const {
  const TaskStats& st = schedule_.stats(i);
  return st.steps == 0 ? Duration::zero() : st.total_step / static_cast<std::int64_t>(st.steps);
}

TimePoint LockstepExecutor::step() {
  const TimePoint t = schedule_.next_release();
  if (t == TimePoint::max()) return clock_.now_;  // empty table
  clock_.now_ = t;
  const std::size_t n = schedule_.size();
  std::size_t i = 0;
  for (; i < n && schedule_.entry(i).lane == 0; ++i)
    run_row(i, t);
  // The lanes with a row released now (lanes are contiguous: they never decrease).
  released_lanes_.clear();
  Duration expected = Duration::zero();
  while (i < n) {
    const std::size_t begin = i;
    const int lane = schedule_.entry(i).lane;
    bool released = false;
    for (; i < n && schedule_.entry(i).lane == lane; ++i) {
      if (schedule_.release_of(i) != t) continue;
      released = true;
      expected += mean_step(i);
    }
    if (released) (void)released_lanes_.push_back({begin, i});
  }
  if (released_lanes_.empty()) return t;
  const auto run_lane = [&](int k) {
    const Rows& lane = released_lanes_[static_cast<std::size_t>(k)];
    for (std::size_t r = lane.begin; r < lane.end; ++r)
      run_row(r, t);
  };
  const int lanes = static_cast<int>(released_lanes_.size());
  if (fork_join_ != nullptr && lanes > 1 && (stopwatch_ == nullptr || expected >= kWorthForking)) {
    fork_join_->run(lanes, run_lane);
  } else {
    for (int k = 0; k < lanes; ++k)
      run_lane(k);
  }
  if (barrier_ != nullptr) barrier_->lanes_done(t);
  return t;
}

void LockstepExecutor::run_until(TimePoint end) {
  while (schedule_.next_release() <= end)
    step();
  clock_.now_ = end;
}

}  // namespace colag::platform
