// Recording a mission as MCAP (colag_sim --mcap) only watches it: what the mission measures is
// the same as without the recording, to the last digit of the JSON.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "colag/sim/mission/mission.hpp"
#include "colag/sim/recording/mcap_recorder.hpp"

namespace colag::mission {
namespace {

TEST(Mission, RecordingItAsMcapChangesNothingItMeasures) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.world = sim::field_world();
  cfg.ugvs = 2;
  cfg.seed = 5;
  cfg.max_time_s = 120;
  std::string error;
  const auto plain = run_mission(cfg, nullptr, &error);
  ASSERT_TRUE(plain) << error;

  const std::string file = testing::TempDir() + "recording_" + std::to_string(::getpid()) + ".mcap";
  McapRecorder recorder;
  ASSERT_TRUE(recorder.open(file, error)) << error;
  const auto recorded = run_mission(cfg, nullptr, &error, &recorder);
  ASSERT_TRUE(recorded) << error;
  ASSERT_TRUE(recorder.close(error)) << error;
  EXPECT_GT(recorder.messages(), 1000U);
  std::remove(file.c_str());

  EXPECT_EQ(to_json(plain.value(), /*include_wall_time=*/false),
            to_json(recorded.value(), /*include_wall_time=*/false));
}

}  // namespace
}  // namespace colag::mission
