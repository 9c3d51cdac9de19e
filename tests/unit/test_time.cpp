#include <gtest/gtest.h>

#include "colag/common/time.hpp"

using namespace colag;
using namespace std::chrono_literals;

TEST(Time, SecondsRoundTripToTheNanosecond) {
  EXPECT_EQ(seconds(1.5), 1500ms);
  EXPECT_EQ(seconds(0.1).count(), 100'000'000);
  EXPECT_EQ(seconds(-0.25), -250ms);
  EXPECT_EQ(seconds(1e-9).count(), 1);
  EXPECT_EQ(seconds(0.4e-9).count(), 0);
  EXPECT_DOUBLE_EQ(to_seconds(2500ms), 2.5);
  EXPECT_DOUBLE_EQ(to_seconds(time_at_seconds(12.25)), 12.25);
}

TEST(Time, PeriodOfRate) {
  EXPECT_EQ(period_of_hz(50.0), 20ms);
  EXPECT_EQ(period_of_hz(10.0), 100ms);
  EXPECT_EQ(period_of_hz(3.0).count(), 333'333'333);
}

TEST(Time, Int64NanosecondsCoverCenturies) {
  EXPECT_GT(TimePoint::max().time_since_epoch(), std::chrono::hours(24 * 365 * 290));
}
