#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "allocation_counter.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/common/static_vector.hpp"

using colag::test::AllocationCounter;

namespace {
// Keeps the optimiser from removing an allocation whose result is unused.
template <class T>
void keep(T&& value) {
  asm volatile("" : : "g"(&value) : "memory");
}
}  // namespace

TEST(AllocationCounter, CountsOperatorNew) {
  AllocationCounter counter;
  auto p = std::make_unique<int>(5);
  keep(p);
  EXPECT_EQ(counter.count(), 1u);
}

TEST(AllocationCounter, CountsContainerGrowth) {
  AllocationCounter counter;
  std::vector<int> v;
  for (int i = 0; i < 100; ++i)
    v.push_back(i);  // NOLINT(performance-inefficient-vector-operation): allocating is the point
  keep(v);
  EXPECT_GE(counter.count(), 5u);  // 1, 2, 4, ..., 128
}

TEST(AllocationCounter, CountsCAllocations) {
  AllocationCounter counter;
  void* a = std::malloc(64);
  keep(a);
  void* b = std::calloc(4, 16);
  keep(b);
  a = std::realloc(a, 4096);
  keep(a);
  std::free(a);
  std::free(b);
  EXPECT_EQ(counter.count(), 3u);
}

TEST(AllocationCounter, CountsLongStrings) {
  AllocationCounter counter;
  std::string s(200, 'x');
  keep(s);
  EXPECT_EQ(counter.count(), 1u);
}

TEST(AllocationCounter, StaticContainersAndArithmeticAllocateNothing) {
  AllocationCounter counter;
  colag::StaticVector<double, 64> v;
  colag::RingBuffer<double, 16> r;
  double acc = 0;
  for (int i = 0; i < 1000; ++i) {
    if (v.full()) v.clear();
    ASSERT_TRUE(v.push_back(i * 0.5));
    r.push_overwrite(acc);
    acc += v.back() * 1.0001;
  }
  keep(acc);
  EXPECT_EQ(counter.count(), 0u);
}

// By default every thread counts: work a task hands to a worker thread is the task's work.
TEST(AllocationCounter, CountsOtherThreadsByDefault) {
  std::unique_ptr<int> from_other;
  AllocationCounter counter;
  std::thread worker([&] { from_other = std::make_unique<int>(1); });
  worker.join();
  EXPECT_GE(counter.count(), 1u);
  EXPECT_NE(from_other, nullptr);
}

// Counting one thread: beside a library whose own threads allocate by design (Cyclone DDS).
TEST(AllocationCounter, CanCountTheCallingThreadOnly) {
  std::atomic<int> phase{0};
  std::unique_ptr<int> from_other;
  std::thread worker([&] {
    while (phase.load() != 1)
      std::this_thread::yield();
    from_other = std::make_unique<int>(1);
    phase.store(2);
  });
  {
    AllocationCounter counter(AllocationCounter::Threads::kThisOne);
    phase.store(1);
    while (phase.load() != 2)
      std::this_thread::yield();
    EXPECT_EQ(counter.count(), 0u);
    auto mine = std::make_unique<int>(2);
    keep(mine);
    EXPECT_EQ(counter.count(), 1u);
  }
  worker.join();
  EXPECT_NE(from_other, nullptr);
}
