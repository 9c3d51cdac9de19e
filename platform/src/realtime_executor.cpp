#include "colag/platform/realtime_executor.hpp"

#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <ctime>

namespace colag::platform {

namespace {

Status errno_status(int err, const char* what) {
  if (err == EPERM || err == EACCES) return {Errc::kPermissionDenied, what};
  return {Errc::kIoError, what};
}

void sleep_until(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  // EINTR (a signal) just returns early; the run loop re-checks the time and the stop flag.
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace

RealtimeSetup RealtimeExecutor::apply(const RealtimeOptions& options) {
  RealtimeSetup out;
  out.fifo_requested = options.fifo_priority > 0;
  out.memory_lock_requested = options.lock_memory;
  if (out.fifo_requested) {
    sched_param sp{};
    sp.sched_priority = options.fifo_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0) {
      out.fifo = errno_status(errno, "refused (needs CAP_SYS_NICE or RLIMIT_RTPRIO)");
    }
  }
  if (options.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    out.memory_lock = errno_status(errno, "refused (needs CAP_IPC_LOCK or RLIMIT_MEMLOCK)");
  }
  return out;
}

std::uint64_t RealtimeExecutor::run_until(TimePoint end) {
  std::uint64_t activations = 0;
  while (!stop_.load(std::memory_order_relaxed)) {
    const TimePoint release = schedule_.next_release();
    if (release > end) break;
    const TimePoint now = clock_.now();
    if (now < release) {
      sleep_until(clock_.monotonic_ns(release));
      continue;  // re-check the stop flag and the time (a signal may have woken us early)
    }
    // Every row released by now runs, in table order, with its scheduled release as `now`.
    for (std::size_t i = 0; i < schedule_.size(); ++i) {
      if (schedule_.release_of(i) > now) continue;
      const TimePoint started = clock_.now();
      schedule_.entry(i).task->step(schedule_.release_of(i));
      const TimePoint finished = clock_.now();
      if (schedule_.complete(i, started, finished - started, finished))
        schedule_.entry(i).task->on_overrun(finished - started);
      ++activations;
    }
  }
  return activations;
}

}  // namespace colag::platform
