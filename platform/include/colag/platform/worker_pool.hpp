#pragma once
// ForkJoin on real threads: `extra_threads` workers started once (at program start, never in a
// step; the constructor returns when every worker runs, so no part of a thread's start-up,
// which may allocate, falls in a step) plus the calling thread, which runs parts too. run()
// allocates nothing; the parts of one call are claimed in order by whichever thread is free,
// and run() returns when all are done. A worker that wakes late does no harm: the caller
// claims the parts no one has started. But waking a sleeping thread takes long enough (~0.1 ms
// on a virtual machine) that short jobs would run on the caller alone, so an idle worker first
// spins for `spin` (a step that forks usually forks again soon), then sleeps.
//
// A part may call run() again (the simulator's lanes run robots side by side, and the UAV's
// lane splits its scan insertion): the inner job joins the jobs in flight, its caller works on
// it, and a thread that runs out of work takes a part of the newest job first (the one some
// caller waits for). A caller only ever waits for parts already running, so nesting cannot
// deadlock. Past kMaxJobs jobs in flight, run() runs the parts itself, one after the other.
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "colag/common/fork_join.hpp"
#include "colag/common/time.hpp"

namespace colag::platform {

class WorkerPool final : public ForkJoin {
 public:
  explicit WorkerPool(int extra_threads, Duration spin = std::chrono::microseconds(200));
  ~WorkerPool() override;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int concurrency() const override { return static_cast<int>(threads_.size()) + 1; }
  void run(int parts, FunctionRef<void(int)> part) override;

  static constexpr std::size_t kMaxJobs = 8;  // in flight at once (nested or from other threads)

 private:
  struct Job {
    const FunctionRef<void(int)>* part = nullptr;  // nullptr: a free slot
    int parts = 0, next = 0, finished = 0;
    std::uint64_t order = 0;  // when it started: the newest is served first
  };
  void worker_main();
  // The newest job with a part no one has started, or nullptr; under the lock.
  Job* claimable();
  // Runs part `i` of `job` (claimed under the lock); `lock` is held on entry and exit.
  void run_part(Job& job, int i, std::unique_lock<std::mutex>& lock);

  std::mutex mutex_;
  std::condition_variable wake_;  // a new job, or stop
  std::condition_variable done_;  // the last part of a job finished, or a worker started
  std::array<Job, kMaxJobs> jobs_{};
  int started_ = 0;                           // workers running
  std::atomic<std::uint64_t> generation_{0};  // one more per job (written under the mutex)
  Duration spin_;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace colag::platform
