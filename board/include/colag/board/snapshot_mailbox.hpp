#pragma once
// Hands a copy of a task's state to a thread of its own (the ROS 2 telemetry: DDS allocates and
// may block, so it never runs on a task's thread). Two snapshots: the task fills the free one
// (try-lock: never waits; a busy mailbox skips the period) and wakes the thread, which swaps
// it for the one it publishes from. The thread also calls `each_wake` (to take commands in).
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <semaphore>
#include <thread>
#include <utility>

namespace colag::board {

template <class Snapshot>
class SnapshotMailbox {
 public:
  SnapshotMailbox() : next_(std::make_unique<Snapshot>()), work_(std::make_unique<Snapshot>()) {}
  ~SnapshotMailbox() { stop(); }
  SnapshotMailbox(const SnapshotMailbox&) = delete;
  SnapshotMailbox& operator=(const SnapshotMailbox&) = delete;

  // Both snapshots, to size them before start (their capacities are fixed from then on).
  template <class Init>
  void init(Init&& init) {
    init(*next_);
    init(*work_);
  }
  void start(std::function<void(const Snapshot&)> publish, std::function<void()> each_wake) {
    publish_ = std::move(publish);
    each_wake_ = std::move(each_wake);
    thread_ = std::thread([this] { loop(); });
  }
  // The task's thread: `fill(Snapshot&)` into the free snapshot, then wake the thread. False
  // (nothing filled) when the thread holds the lock for a moment.
  template <class Fill>
  bool offer(Fill&& fill) {
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return false;
    fill(*next_);
    fresh_ = true;
    lock.unlock();
    wake_.release();
    return true;
  }
  void stop() {
    if (!thread_.joinable()) return;
    stopping_.store(true);
    wake_.release();
    thread_.join();
  }

 private:
  void loop() {
    for (;;) {
      wake_.acquire();
      if (stopping_.load()) return;
      if (each_wake_) each_wake_();
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!fresh_) continue;
        std::swap(next_, work_);
        fresh_ = false;
      }
      publish_(*work_);
    }
  }

  std::mutex mutex_;
  std::unique_ptr<Snapshot> next_, work_;
  bool fresh_ = false;
  std::counting_semaphore<> wake_{0};
  std::atomic<bool> stopping_{false};
  std::function<void(const Snapshot&)> publish_;
  std::function<void()> each_wake_;
  std::thread thread_;
};

}  // namespace colag::board
