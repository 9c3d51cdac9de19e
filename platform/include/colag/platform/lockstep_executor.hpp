#pragma once
// Runs a schedule on simulated time: no sleeping, tasks run back to back in release order
// (ties in table order), and the clock jumps from one release to the next. Same table, same
// inputs => the same run, bit for bit.
#include "colag/hal/clock.hpp"
#include "colag/platform/schedule.hpp"

namespace colag::platform {

class LockstepExecutor {
 public:
  // `stopwatch` (optional, e.g. a MonotonicClock) only measures how long steps take on the
  // host, for the statistics; it never influences what runs when.
  explicit LockstepExecutor(TimePoint start = TimePoint{}, const hal::Clock* stopwatch = nullptr);

  Status add(const TaskEntry& entry) { return schedule_.add(entry); }
  Status init() { return schedule_.init(clock_.now()); }

  // The simulated clock: hand it to the devices and tasks of the simulated robots.
  const hal::Clock& clock() const { return clock_; }
  TimePoint now() const { return clock_.now(); }

  // Runs the next release instant (every task due then) and returns it.
  TimePoint step();
  // Runs every activation released at or before `end`; afterwards now() == end.
  void run_until(TimePoint end);

  const Schedule& schedule() const { return schedule_; }

 private:
  class SimClock final : public hal::Clock {
   public:
    TimePoint now() const override { return now_; }
    TimePoint now_{};
  };
  SimClock clock_;
  const hal::Clock* stopwatch_;
  Schedule schedule_;
};

}  // namespace colag::platform
