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
  if (threads_.empty() || parts == 1) {
    for (int i = 0; i < parts; ++i)
      part(i);
    return;
  }
  std::unique_lock lock(mutex_);
  job_ = &part;
  parts_ = parts;
  next_ = 0;
  finished_ = 0;
  ++generation_;
  wake_.notify_all();
  run_parts(lock);
  done_.wait(lock, [&] { return finished_ == parts_; });
  job_ = nullptr;
}

void WorkerPool::run_parts(std::unique_lock<std::mutex>& lock) {
  while (job_ != nullptr && next_ < parts_) {
    const int i = next_++;
    const FunctionRef<void(int)>& part = *job_;
    lock.unlock();
    part(i);
    lock.lock();
    if (++finished_ == parts_) done_.notify_all();
  }
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
    seen = generation_.load();
    run_parts(lock);
  }
}

}  // namespace colag::platform
