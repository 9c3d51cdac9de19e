#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <set>
#include <thread>

#include "allocation_counter.hpp"
#include "colag/platform/worker_pool.hpp"

using namespace colag;

TEST(WorkerPool, RunsEveryPartExactlyOnceAndReturnsWhenAllAreDone) {
  for (int extra : {0, 1, 3}) {
    platform::WorkerPool pool(extra);
    EXPECT_EQ(pool.concurrency(), extra + 1);
    for (int round = 0; round < 200; ++round) {
      const int parts = 1 + round % 7;
      std::array<std::atomic<int>, 8> runs{};
      pool.run(parts, [&](int k) { runs[static_cast<std::size_t>(k)].fetch_add(1); });
      for (int k = 0; k < 8; ++k)
        EXPECT_EQ(runs[static_cast<std::size_t>(k)].load(), k < parts ? 1 : 0);
    }
    pool.run(0, [](int) { FAIL() << "no parts, no calls"; });
  }
}

TEST(WorkerPool, UsesTheWorkerThreadsWhenThePartsTakeTime) {
  platform::WorkerPool pool(1);
  std::set<std::thread::id> seen;
  std::array<std::thread::id, 2> who{};
  for (int round = 0; round < 20 && seen.size() < 2; ++round) {
    pool.run(2, [&](int k) {
      who[static_cast<std::size_t>(k)] = std::this_thread::get_id();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    });
    seen.insert(who.begin(), who.end());
  }
  EXPECT_EQ(seen.size(), 2u) << "the worker never took a part";
}

TEST(WorkerPool, RunAllocatesNothingOnAnyThread) {
  platform::WorkerPool pool(1);
  int sum[2] = {0, 0};
  pool.run(2, [&](int k) { sum[k] += 1; });  // warm up
  test::AllocationCounter counter;
  for (int i = 0; i < 1000; ++i)
    pool.run(2, [&](int k) { sum[k] += 1; });
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(sum[0] + sum[1], 2002);
}

// The simulator's lanes run robots side by side on the pool, and the UAV's lane splits its scan
// insertion on the same pool: a part may fork again, to any depth, from any thread.
TEST(WorkerPool, APartMayForkAgainAndEveryNestedPartRunsOnce) {
  for (int extra : {1, 3}) {
    platform::WorkerPool pool(extra);
    for (int round = 0; round < 50; ++round) {
      std::array<std::array<std::atomic<int>, 5>, 6> runs{};
      pool.run(6, [&](int outer) {
        pool.run(5, [&](int inner) {
          runs[static_cast<std::size_t>(outer)][static_cast<std::size_t>(inner)].fetch_add(1);
        });
      });
      for (const auto& row : runs)
        for (const auto& n : row)
          EXPECT_EQ(n.load(), 1);
    }
  }
}

TEST(WorkerPool, NestingDeeperThanItsJobSlotsRunsTheRestInPlace) {
  platform::WorkerPool pool(1);
  std::atomic<int> leaves{0};
  // Two parts at every level, 12 levels: up to 12 jobs in flight on one call path, more than
  // the pool keeps; every leaf still runs exactly once.
  const std::function<void(int)> fork = [&](int depth) {
    if (depth == 0) {
      leaves.fetch_add(1);
      return;
    }
    pool.run(2, [&](int) { fork(depth - 1); });
  };
  fork(12);
  EXPECT_EQ(leaves.load(), 1 << 12);
}

TEST(WorkerPool, AWorkerHelpsWithANestedJobWhileTheOuterCallerWaits) {
  platform::WorkerPool pool(1);
  std::set<std::thread::id> inner_threads;
  std::mutex m;
  for (int round = 0; round < 20 && inner_threads.size() < 2; ++round) {
    // Part 0 forks two slow parts; part 1 is quick: the worker that took it must find the
    // nested job's second part.
    pool.run(2, [&](int outer) {
      if (outer == 1) return;
      pool.run(2, [&](int) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        const std::lock_guard lock(m);
        inner_threads.insert(std::this_thread::get_id());
      });
    });
  }
  EXPECT_EQ(inner_threads.size(), 2u) << "a nested job ran on its caller alone";
}

TEST(WorkerPool, NestedRunsAllocateNothing) {
  platform::WorkerPool pool(1);
  int sum[2][2] = {{0, 0}, {0, 0}};
  const auto nested = [&] {
    pool.run(2, [&](int a) { pool.run(2, [&](int b) { sum[a][b] += 1; }); });
  };
  nested();  // warm up
  test::AllocationCounter counter;
  for (int i = 0; i < 500; ++i)
    nested();
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(sum[0][0] + sum[0][1] + sum[1][0] + sum[1][1], 4 * 501);
}

TEST(SerialForkJoin, RunsThePartsInOrder) {
  SerialForkJoin serial;
  std::vector<int> order;
  serial.run(4, [&](int k) { order.push_back(k); });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(serial.concurrency(), 1);
}
