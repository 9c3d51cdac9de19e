#pragma once
// Runs a schedule on simulated time: no sleeping, tasks run back to back in release order
// (ties in table order), and the clock jumps from one release to the next. Same table, same
// inputs => the same run, bit for bit.
//
// Lanes: when several robots are simulated in one table, each robot's tasks may form a lane
// (TaskEntry::lane >= 1; lanes never decrease along the table). At each instant the rows of
// lane 0 run first, in table order; then the lanes released at that instant, each lane's rows
// in table order, and different lanes at the same time when set_lanes() gave a ForkJoin.
// That is the same run as the table in order on one thread when the lanes touch nothing that
// another lane touches and publish through LaneOutboxes, which the LaneBarrier flushes in
// lane order after the lanes ran (robots only meet through the transport, and a sample
// published at an instant is delivered at a later poll anyway).
#include "colag/common/fork_join.hpp"
#include "colag/hal/clock.hpp"
#include "colag/platform/schedule.hpp"

namespace colag::platform {

class LaneBarrier {
 public:
  // Called after the lanes released at `now` ran (on the executor's thread).
  virtual void lanes_done(TimePoint now) = 0;

 protected:
  ~LaneBarrier() = default;
};

class LockstepExecutor {
 public:
  // `stopwatch` (optional, e.g. a MonotonicClock) only measures how long steps take on the
  // host, for the statistics; it never influences what runs when.
  explicit LockstepExecutor(TimePoint start = TimePoint{}, const hal::Clock* stopwatch = nullptr);

  Status add(const TaskEntry& entry) { return schedule_.add(entry); }
  Status add(std::span<const TaskEntry> entries) { return schedule_.add(entries); }
  Status init() { return schedule_.init(clock_.now()); }
  // Lets lanes run at the same time on `fork_join` (optional; not owned; a lane's tasks may
  // fork on it too when it allows nested runs, as WorkerPool does) and names who flushes their
  // outboxes (optional; not owned).
  void set_lanes(ForkJoin* fork_join, LaneBarrier* barrier) {
    fork_join_ = fork_join;
    barrier_ = barrier;
  }

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
  // Runs row i if it is released at t.
  void run_row(std::size_t i, TimePoint t);
  // The mean step time of row i so far (zero without a stopwatch).
  Duration mean_step(std::size_t i) const;
  struct Rows {
    std::size_t begin = 0, end = 0;
  };

  SimClock clock_;
  const hal::Clock* stopwatch_;
  Schedule schedule_;
  ForkJoin* fork_join_ = nullptr;
  LaneBarrier* barrier_ = nullptr;
  StaticVector<Rows, limits::kMaxTasksPerExecutor> released_lanes_;  // of the current instant
};

}  // namespace colag::platform
