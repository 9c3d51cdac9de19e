#include "colag/platform/worker_pool.hpp"

#include <chrono>

namespace colag::platform {

WorkerPool::WorkerPool(int extra_threads, Duration spin) : spin_(spin) {
  for (int i = 0; i < extra_threads; ++i)
    threads_.emplace_back([this] { worker_main(); });
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return started_ == static_cast<int>(threads_.size()); });
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_)
    t.join();
}

void WorkerPool::run(int parts, FunctionRef<void(int)> part) {
  if (parts <= 0) return;
  const auto serial = [&] {
    for (int i = 0; i < parts; ++i)
      part(i);
  };
  if (threads_.empty() || parts == 1) return serial();
  std::unique_lock lock(mutex_);
  Job* job = nullptr;
  for (Job& j : jobs_) {
    if (j.part == nullptr) {
      job = &j;
      break;
    }
  }
  if (job == nullptr) {  // too deep: no one else could take these parts sooner than we do
    lock.unlock();
    return serial();
  }
  *job = {&part, parts, 0, 0, ++generation_};
  wake_.notify_all();
  while (job->next < job->parts)
    run_part(*job, job->next++, lock);
  // Until the parts others took are done, help with any job in flight (a part of this one's
  // parent, at the most, is one part late here).
  while (job->finished != job->parts) {
    if (Job* other = claimable(); other != nullptr) {
      run_part(*other, other->next++, lock);
    } else {
      done_.wait(lock);
    }
  }
  job->part = nullptr;
}

WorkerPool::Job* WorkerPool::claimable() {
  Job* newest = nullptr;
  for (Job& j : jobs_) {
    if (j.part != nullptr && j.next < j.parts && (newest == nullptr || j.order > newest->order))
      newest = &j;
  }
  return newest;
}

void WorkerPool::run_part(Job& job, int i, std::unique_lock<std::mutex>& lock) {
  const FunctionRef<void(int)> part = *job.part;
  lock.unlock();
  part(i);
  lock.lock();
  if (++job.finished == job.parts) done_.notify_all();
}

void WorkerPool::worker_main() {
  std::uint64_t seen = 0;
  {
    const std::lock_guard lock(mutex_);
    seen = generation_.load();
    ++started_;
  }
  done_.notify_all();
  for (;;) {
    const auto until = std::chrono::steady_clock::now() + spin_;
    while (generation_.load(std::memory_order_relaxed) == seen &&
           std::chrono::steady_clock::now() < until) {
      std::this_thread::yield();
    }
    std::unique_lock lock(mutex_);
    wake_.wait(lock, [&] { return stop_ || generation_.load() != seen; });
    if (stop_) return;
    for (Job* job = claimable(); job != nullptr; job = claimable())
      run_part(*job, job->next++, lock);
    seen = generation_.load();  // every job started so far has all its parts taken
  }
}

}  // namespace colag::platform
