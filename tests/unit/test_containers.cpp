#include <gtest/gtest.h>

#include "colag/common/ring_buffer.hpp"
#include "colag/common/static_vector.hpp"

using colag::RingBuffer;
using colag::StaticVector;

TEST(StaticVector, RefusesPastCapacity) {
  StaticVector<int, 3> v;
  EXPECT_TRUE(v.empty());
  EXPECT_TRUE(v.push_back(1));
  EXPECT_TRUE(v.push_back(2));
  EXPECT_TRUE(v.push_back(3));
  EXPECT_TRUE(v.full());
  EXPECT_FALSE(v.push_back(4));
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 1);
  EXPECT_EQ(v.back(), 3);
}

TEST(StaticVector, SwapRemoveResizeAndIterate) {
  StaticVector<int, 5> v;
  for (int i = 0; i < 5; ++i)
    ASSERT_TRUE(v.push_back(i * 10));
  v.swap_remove(1);  // 0 40 20 30
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[1], 40);
  int sum = 0;
  for (int x : v)
    sum += x;
  EXPECT_EQ(sum, 90);
  EXPECT_FALSE(v.resize(6));
  EXPECT_TRUE(v.resize(2));
  EXPECT_TRUE(v.resize(3));
  EXPECT_EQ(v[2], 0);  // regrown slots are default values, not stale ones
  v.clear();
  EXPECT_TRUE(v.empty());
}

TEST(RingBuffer, FifoOrderAcrossWrapAround) {
  RingBuffer<int, 4> r;
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 3; ++i)
      ASSERT_TRUE(r.try_push(round * 10 + i));
    for (int i = 0; i < 3; ++i) {
      int out = -1;
      ASSERT_TRUE(r.pop_front(out));
      EXPECT_EQ(out, round * 10 + i);
    }
  }
  int out = 0;
  EXPECT_FALSE(r.pop_front(out));
}

TEST(RingBuffer, TryPushRefusesWhenFullPushOverwriteDropsOldest) {
  RingBuffer<int, 3> r;
  EXPECT_FALSE(r.push_overwrite(1));
  EXPECT_FALSE(r.push_overwrite(2));
  EXPECT_FALSE(r.push_overwrite(3));
  EXPECT_FALSE(r.try_push(4));
  EXPECT_TRUE(r.push_overwrite(4));  // dropped 1
  EXPECT_TRUE(r.push_overwrite(5));  // dropped 2
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0], 3);
  EXPECT_EQ(r[1], 4);
  EXPECT_EQ(r.back(), 5);
}

TEST(StaticVector, InsertAtAndEraseAtKeepTheOrder) {
  colag::StaticVector<int, 4> v;
  ASSERT_TRUE(v.insert_at(0, 2));
  ASSERT_TRUE(v.insert_at(0, 1));
  ASSERT_TRUE(v.insert_at(2, 4));
  ASSERT_TRUE(v.insert_at(2, 3));
  EXPECT_FALSE(v.insert_at(1, 9));  // full: unchanged
  ASSERT_EQ(v.size(), 4u);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(v[static_cast<std::size_t>(i)], i + 1);
  v.erase_at(1);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 1);
  EXPECT_EQ(v[1], 3);
  EXPECT_EQ(v[2], 4);
  v.erase_at(2);
  EXPECT_EQ(v.size(), 2u);
  EXPECT_EQ(v.back(), 3);
}
