#pragma once
// Runs a schedule in real time on Linux: one thread sleeps with clock_nanosleep(TIMER_ABSTIME)
// on CLOCK_MONOTONIC until the next release, then runs the due tasks in table order. Absolute
// sleeps do not accumulate drift. Overruns (step > budget) and skipped activations (a task
// more than one period late) are counted per task, never hidden.
#include <atomic>

#include "colag/platform/monotonic_clock.hpp"
#include "colag/platform/schedule.hpp"

namespace colag::platform {

struct RealtimeOptions {
  int fifo_priority = 0;     // 1..99 to request SCHED_FIFO; 0 keeps the default policy
  bool lock_memory = false;  // mlockall(MCL_CURRENT | MCL_FUTURE): no page faults in steps
};

// The outcome of each request in RealtimeOptions; kPermissionDenied is normal without
// CAP_SYS_NICE / CAP_IPC_LOCK and leaves the executor running without it.
struct RealtimeSetup {
  bool fifo_requested = false;
  bool memory_lock_requested = false;
  Status fifo;         // ok: granted, or not requested
  Status memory_lock;  // ok: granted, or not requested
};

class RealtimeExecutor {
 public:
  // `time_scale` != 1 only for software-in-the-loop runs (see MonotonicClock).
  explicit RealtimeExecutor(double time_scale = 1.0) : clock_(time_scale) {}
  Status add(const TaskEntry& entry) { return schedule_.add(entry); }
  Status add(std::span<const TaskEntry> entries) { return schedule_.add(entries); }
  RealtimeSetup apply(const RealtimeOptions& options);
  // Calls every task's init(); the first releases are at the time of this call (+ offsets).
  Status init() { return schedule_.init(clock_.now()); }

  const hal::Clock& clock() const { return clock_; }
  // Runs until `end` or until request_stop(); returns the number of activations run.
  std::uint64_t run_until(TimePoint end);
  std::uint64_t run() { return run_until(TimePoint::max()); }
  // Async-signal-safe: may be called from a SIGINT/SIGTERM handler or another thread.
  void request_stop() { stop_.store(true, std::memory_order_relaxed); }
  bool stop_requested() const { return stop_.load(std::memory_order_relaxed); }

  const Schedule& schedule() const { return schedule_; }

 private:
  MonotonicClock clock_;
  Schedule schedule_;
  std::atomic<bool> stop_{false};
  static_assert(std::atomic<bool>::is_always_lock_free);
};

}  // namespace colag::platform
