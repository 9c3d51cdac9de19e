#pragma once
// ForkJoin on real threads: `extra_threads` workers started once (at program start, never in a
// step; the constructor returns when every worker runs, so no part of a thread's start-up,
// which may allocate, falls in a step) plus the calling thread, which runs parts too. run()
// allocates nothing; the parts of one call are claimed in order by whichever thread is free,
// and run() returns when all are done. A worker that wakes late does no harm: the caller
// claims the parts no one has started. But waking a sleeping thread takes long enough (~0.1 ms
// on a virtual machine) that short jobs would run on the caller alone, so an idle worker first
// spins for `spin` (a step that forks usually forks again soon), then sleeps.
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

 private:
  void worker_main();
  // Claims and runs parts of the current job until none is left; `lock` is held on entry and exit.
  void run_parts(std::unique_lock<std::mutex>& lock);

  std::mutex mutex_;
  std::condition_variable wake_;  // a new job, or stop
  std::condition_variable done_;  // the last part of a job finished, or a worker started
  const FunctionRef<void(int)>* job_ = nullptr;
  int parts_ = 0, next_ = 0, finished_ = 0;
  int started_ = 0;                           // workers running
  std::atomic<std::uint64_t> generation_{0};  // one more per job (written under the mutex)
  Duration spin_;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace colag::platform
