// A whole mission on two threads (its own file: the ThreadSanitizer build compiles only this
// mission test, in colag_tsan_tests, not the whole mission suite).
#include <gtest/gtest.h>

#include <string>

#include "colag/sim/mission/mission.hpp"

using namespace colag::mission;

namespace {
// The mission's JSON (but for the wall time) flown on two threads, then on one.
void expect_same_on_two_threads_as_on_one(MissionConfig cfg) {
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
}  // namespace

// Each UGV's tasks are a lane of the executor: on two threads the UGVs' planning runs side by
// side (their samples reach the bus in lane order afterwards).
TEST(Mission, UgvLanesOnTwoThreadsFlyTheSameMissionAsOnOne) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 4;
  cfg.seed = 3;
  cfg.max_time_s = 15;
  expect_same_on_two_threads_as_on_one(cfg);
}

// The UAVs' tasks are a lane too (one lane for all UAVs): a UAV's scan insertion runs beside the
// UGVs' planning and forks its halves on the same worker pool. Field world, two UAVs each on its
// own clock: the run on two threads is the run on one, bit for bit.
TEST(Mission, TheUavLaneBesideTheUgvLanesOnTwoThreadsFliesTheSameMission) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 3;
  cfg.uavs = 2;
  cfg.world = colag::sim::field_world();
  cfg.seed = 5;
  cfg.max_time_s = 12;
  expect_same_on_two_threads_as_on_one(cfg);
}
