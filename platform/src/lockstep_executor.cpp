#include "colag/platform/lockstep_executor.hpp"

namespace colag::platform {

LockstepExecutor::LockstepExecutor(TimePoint start, const hal::Clock* stopwatch)
    : stopwatch_(stopwatch) {
  clock_.now_ = start;
}

TimePoint LockstepExecutor::step() {
  const TimePoint t = schedule_.next_release();
  if (t == TimePoint::max()) return clock_.now_;  // empty table
  clock_.now_ = t;
  for (std::size_t i = 0; i < schedule_.size(); ++i) {
    if (schedule_.release_of(i) != t) continue;
    const TimePoint w0 = stopwatch_ ? stopwatch_->now() : TimePoint{};
    schedule_.entry(i).task->step(t);
    const Duration took = stopwatch_ ? stopwatch_->now() - w0 : Duration::zero();
    schedule_.complete(i, t, took, t);
  }
  return t;
}

void LockstepExecutor::run_until(TimePoint end) {
  while (schedule_.next_release() <= end)
    step();
  clock_.now_ = end;
}

}  // namespace colag::platform
