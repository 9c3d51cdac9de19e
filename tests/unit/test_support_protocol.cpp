#include <gtest/gtest.h>

#include "colag/ugv/support_protocol.hpp"

using namespace colag;
using namespace colag::ugv;
using namespace std::chrono_literals;

namespace {
SupportNeed need(double x, double t_pc) {
  return {true, Vec2(x, 0), Vec2(x - 2, 0), t_pc};
}
}  // namespace

TEST(SupportProtocol, SendsOnceThenOnlyOnMaterialChangeOrHeartbeat) {
  SupportProtocol sp;
  msg::CollisionInfo out;
  TimePoint t{10s};
  ASSERT_TRUE(sp.update(t, 3, need(5.0, 8.0), out));
  EXPECT_FALSE(out.cancel);
  EXPECT_EQ(out.ugv_id, 3);
  EXPECT_EQ(out.support_point_m[0], 3.0);
  EXPECT_EQ(out.time_to_collision_s, 8.0);
  // Driving on towards the same point: the absolute collision time does not change.
  t += 100ms;
  EXPECT_FALSE(sp.update(t, 3, need(5.0, 7.9), out));
  // Moved 1 m but the time is the same: not material (both must change).
  t += 100ms;
  EXPECT_FALSE(sp.update(t, 3, need(6.0, 7.8), out));
  // Moved 1 m and 1 s later: resent.
  t += 100ms;
  EXPECT_TRUE(sp.update(t, 3, need(6.0, 8.7), out));
  // Time jumps by more than 3 s alone: resent.
  t += 100ms;
  EXPECT_TRUE(sp.update(t, 3, need(6.0, 12.6), out));
  // Nothing for a second: heartbeat.
  t += 900ms;
  EXPECT_FALSE(sp.update(t, 3, need(6.0, 11.6), out));
  t += 100ms;
  EXPECT_TRUE(sp.update(t, 3, need(6.0, 11.5), out));
}

TEST(SupportProtocol, CancelGoesOutAtOnceAndIsRepeated) {
  SupportProtocol sp;
  msg::CollisionInfo out;
  TimePoint t{1s};
  ASSERT_TRUE(sp.update(t, 1, need(5.0, 4.0), out));
  t += 10ms;  // well inside any rate limit
  ASSERT_TRUE(sp.update(t, 1, SupportNeed{}, out));
  EXPECT_TRUE(out.cancel);
  EXPECT_FALSE(sp.requesting());
  int repeats = 0;
  for (int i = 0; i < 100; ++i) {
    t += 100ms;
    if (sp.update(t, 1, SupportNeed{}, out)) {
      EXPECT_TRUE(out.cancel);
      ++repeats;
    }
  }
  EXPECT_EQ(repeats, 2);  // 3 cancels in all, then silence
}

TEST(SupportProtocol, SequenceNumbersIncrease) {
  SupportProtocol sp;
  msg::CollisionInfo a, b;
  ASSERT_TRUE(sp.update(TimePoint{1s}, 0, need(1, 5), a));
  ASSERT_TRUE(sp.update(TimePoint{1s + 10ms}, 0, SupportNeed{}, b));
  EXPECT_GT(b.seq, a.seq);
}
