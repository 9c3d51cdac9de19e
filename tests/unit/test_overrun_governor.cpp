#include "colag/common/overrun_governor.hpp"

#include <gtest/gtest.h>

using colag::OverrunGovernor;

TEST(OverrunGovernor, OccasionalOverrunsChangeNothing) {
  OverrunGovernor g;  // 3 in a 10-step window degrade
  for (int step = 0; step < 100; ++step) {
    if (step % 5 == 0) g.on_overrun();  // 2 per window
    EXPECT_EQ(g.update(), 0);
  }
  EXPECT_EQ(g.total(), 20u);
}

TEST(OverrunGovernor, PersistentOverrunsDegradeStepByStepThenRecover) {
  OverrunGovernor g;
  int step = 0;
  for (; g.level() < 1; ++step) {
    g.on_overrun();
    g.update();
  }
  EXPECT_EQ(step, 3);  // the third overrun in the window
  for (; g.level() < OverrunGovernor::kMaxLevel; ++step) {
    g.on_overrun();
    g.update();
  }
  EXPECT_EQ(step, 6);
  for (int i = 0; i < 20; ++i) {  // still overrunning: stays at the floor
    g.on_overrun();
    EXPECT_EQ(g.update(), OverrunGovernor::kMaxLevel);
  }
  int clean = 0;
  while (g.level() > 0) {
    g.update();
    ++clean;
  }
  EXPECT_EQ(clean, 100);  // 50 clean steps per level back
}

TEST(OverrunGovernor, AnOverrunRestartsTheRecovery) {
  OverrunGovernor g;
  for (int i = 0; i < 3; ++i) {
    g.on_overrun();
    g.update();
  }
  ASSERT_EQ(g.level(), 1);
  for (int i = 0; i < 49; ++i)
    g.update();
  g.on_overrun();
  g.update();
  for (int i = 0; i < 49; ++i)
    EXPECT_EQ(g.update(), 1);
  EXPECT_EQ(g.update(), 0);
}
