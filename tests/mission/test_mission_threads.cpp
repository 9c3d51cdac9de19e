// A whole mission on two threads (its own file: the ThreadSanitizer build compiles only this
// mission test, in colag_tsan_tests, not the whole mission suite).
#include <gtest/gtest.h>

#include <string>

#include "colag/sim/mission/mission.hpp"

using namespace colag::mission;

// Each UGV's tasks are a lane of the executor: on two threads the UGVs' planning runs side by
// side (their samples reach the bus in lane order afterwards).
TEST(Mission, UgvLanesOnTwoThreadsFlyTheSameMissionAsOnOne) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 4;
  cfg.seed = 3;
  cfg.max_time_s = 15;
  std::string error;
  cfg.threads = 2;
  const auto two = run_mission(cfg, nullptr, &error);
  ASSERT_TRUE(two) << error;
  cfg.threads = 1;
  const auto one = run_mission(cfg, nullptr, &error);
  ASSERT_TRUE(one) << error;
  EXPECT_EQ(to_json(two.value(), /*include_wall_time=*/false),
            to_json(one.value(), /*include_wall_time=*/false));
}
