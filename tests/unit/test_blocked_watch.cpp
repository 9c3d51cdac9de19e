// When a UGV says it is blocked (issue 19, item 1).
#include <gtest/gtest.h>

#include "colag/ugv/blocked_watch.hpp"

using namespace colag;
using namespace colag::ugv;
using namespace std::chrono_literals;
using msg::BlockedReason;

TEST(BlockedWatch, BlockedAfterStandingTheWholeAllowanceThenRetries) {
  BlockedWatch w({60s, 30s});
  TimePoint t{};
  for (; t < TimePoint{} + 59900ms; t += 100ms) {
    w.update(t, BlockedReason::kNoPath);
    ASSERT_FALSE(w.blocked()) << to_seconds(t - TimePoint{});
  }
  w.update(t += 100ms, BlockedReason::kNoPath);
  EXPECT_TRUE(w.blocked());
  EXPECT_EQ(w.reason(), BlockedReason::kNoPath);
  w.update(t += 29s, BlockedReason::kNoPath);
  EXPECT_TRUE(w.blocked());
  w.update(t += 1s, BlockedReason::kNoPath);  // the retry: a fresh allowance
  EXPECT_FALSE(w.blocked());
  w.update(t += 59s, BlockedReason::kNoPath);
  EXPECT_FALSE(w.blocked());
  w.update(t += 1s, BlockedReason::kNotCleared);  // the reason of the moment
  EXPECT_TRUE(w.blocked());
  EXPECT_EQ(w.reason(), BlockedReason::kNotCleared);
  EXPECT_EQ(w.times_blocked(), 2u);
}

TEST(BlockedWatch, MovingClearsItAndRestartsTheAllowance) {
  BlockedWatch w({10s, 30s});
  TimePoint t{};
  w.update(t, BlockedReason::kRobotInTheWay);
  w.update(t += 10s, BlockedReason::kRobotInTheWay);
  ASSERT_TRUE(w.blocked());
  w.update(t += 100ms, BlockedReason::kNone);  // it drove off
  EXPECT_FALSE(w.blocked());
  w.update(t += 100ms, BlockedReason::kNotCleared);
  w.update(t += 9s, BlockedReason::kNotCleared);
  EXPECT_FALSE(w.blocked());  // standing again only 9 s
}
