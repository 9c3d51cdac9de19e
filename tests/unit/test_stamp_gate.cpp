// The stamp checks of an input stream: future, age, order, and a sender whose clock went back.
#include <gtest/gtest.h>

#include "colag/common/stamp_gate.hpp"

using namespace colag;
using namespace std::chrono_literals;
using V = StampGate::Verdict;

namespace {
TimePoint at(Duration d) {
  return TimePoint{d};
}
}  // namespace

TEST(StampGate, RefusesTheFutureAndThePastAndNeverLetsTheFutureLockTheStreamOut) {
  StampGate g({200ms, 2s, true});
  EXPECT_EQ(g.check(at(10s), at(10s)), V::kAccepted);
  EXPECT_EQ(g.check(at(10s + 1h), at(10s + 20ms)), V::kFromTheFuture);
  EXPECT_EQ(g.check(at(10s + 40ms), at(10s + 40ms)), V::kAccepted);  // not locked out
  EXPECT_EQ(g.check(at(7s), at(10s + 60ms)), V::kTooOld);
  EXPECT_EQ(g.check(at(10s + 250ms), at(10s + 60ms)), V::kAccepted);  // within the skew
  EXPECT_EQ(g.counters().from_future, 1u);
  EXPECT_EQ(g.counters().too_old, 1u);
  EXPECT_EQ(g.counters().accepted, 3u);
}

TEST(StampGate, DropsDuplicatesAndOvertakenSamplesOnlyWhenAskedTo) {
  StampGate ordered({200ms, 2s, true});
  StampGate unordered({200ms, 2s, false});
  for (StampGate* g : {&ordered, &unordered}) {
    EXPECT_TRUE(StampGate::passed(g->check(at(5s), at(5s))));
  }
  EXPECT_EQ(ordered.check(at(5s), at(5s + 10ms)), V::kNotIncreasing);      // duplicate
  EXPECT_EQ(ordered.check(at(4900ms), at(5s + 20ms)), V::kNotIncreasing);  // overtaken
  EXPECT_EQ(unordered.check(at(4900ms), at(5s + 20ms)), V::kAccepted);     // a late RPE is fine
  // Overtaken samples, however many, are no restart: they are within the reorder bound.
  for (int k = 1; k <= 5; ++k)
    EXPECT_EQ(ordered.check(at(4800ms + k * 10ms), at(5s + 30ms)), V::kNotIncreasing);
  EXPECT_EQ(ordered.counters().restarts, 0u);
}

TEST(StampGate, FollowsASenderWhoseClockWentBack) {
  StampGate g({200ms, 10s, true});
  EXPECT_EQ(g.check(at(20s), at(20s)), V::kAccepted);
  // The sender's clock steps back 5 s: three samples in a row, increasing, far behind.
  EXPECT_EQ(g.check(at(15s), at(20s + 100ms)), V::kNotIncreasing);
  EXPECT_EQ(g.check(at(15s + 100ms), at(20s + 200ms)), V::kNotIncreasing);
  EXPECT_EQ(g.check(at(15s + 200ms), at(20s + 300ms)), V::kRestarted);
  EXPECT_EQ(g.check(at(15s + 300ms), at(20s + 400ms)), V::kAccepted);
  EXPECT_EQ(g.counters().restarts, 1u);
  // Far behind but not increasing among themselves: not a timeline, no restart.
  StampGate h({200ms, 10s, true});
  EXPECT_EQ(h.check(at(20s), at(20s)), V::kAccepted);
  EXPECT_EQ(h.check(at(15s), at(20s)), V::kNotIncreasing);
  EXPECT_EQ(h.check(at(14s), at(20s)), V::kNotIncreasing);
  EXPECT_EQ(h.check(at(13s), at(20s)), V::kNotIncreasing);
  EXPECT_EQ(h.counters().restarts, 0u);
}
