#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
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

TEST(SerialForkJoin, RunsThePartsInOrder) {
  SerialForkJoin serial;
  std::vector<int> order;
  serial.run(4, [&](int k) { order.push_back(k); });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(serial.concurrency(), 1);
}
