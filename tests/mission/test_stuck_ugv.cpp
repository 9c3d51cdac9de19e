// One UGV that cannot be helped must not starve the others (issue 19, item 1): it reports
// itself blocked with the reason, withdraws its request, and the others reach their goals.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "colag/sim/mission/mission.hpp"
#include "colag/sim/world/pcd_writer.hpp"

using namespace colag;
using namespace colag::mission;

namespace {

// The sparse map of seed 1 with `extra` obstacles, written as the PCD a user would give.
std::string map_with(const std::vector<sim::Box>& extra, const std::string& name) {
  MissionConfig base;
  base.scenario = "sparse";
  sim::BoxWorld world;
  std::string error;
  EXPECT_TRUE(build_world(base, world, error)) << error;
  world.boxes.insert(world.boxes.end(), extra.begin(), extra.end());
  const auto path = std::filesystem::temp_directory_path() /
                    ("colag_" + name + "_" + std::to_string(::getpid()) + ".pcd");
  EXPECT_TRUE(sim::save_pcd(path.string(), world, error)) << error;
  return path.string();
}

MissionOutcome run_on(const std::string& map) {
  MissionConfig cfg;
  cfg.scenario = "file";
  cfg.map_file = map;
  cfg.ugvs = 3;
  cfg.seed = 1;
  cfg.max_time_s = 200;
  std::string error;
  auto out = run_mission(cfg, nullptr, &error);
  std::filesystem::remove(map);
  EXPECT_TRUE(out) << error;
  return out ? out.value() : MissionOutcome{};
}

void expect_the_others_reach(const MissionOutcome& o) {
  ASSERT_EQ(o.ugvs.size(), 3u);
  for (int i : {1, 2}) {
    const UgvOutcome& u = o.ugvs[static_cast<std::size_t>(i)];
    EXPECT_TRUE(u.reached) << "UGV " << i << ": " << u.end;
    EXPECT_FALSE(u.collided) << "UGV " << i;
    EXPECT_LT(u.reach_time_s, 150.0) << "UGV " << i;
  }
  EXPECT_EQ(exit_code(o), 1);  // not every UGV reached
}

}  // namespace

// The case: a box on UGV 0's start hides its tag, so it is never localised. Its
// neighbours, 2 m away inside its uncertainty disc, used to stand still for the whole mission.
TEST(StuckUgv, ABoxOnOneStartDoesNotStopTheOthers) {
  const std::string map = map_with({{Vec2(0.0, 16.0), Vec2(0.4, 0.4), 0.8}}, "box_on_start");
  const MissionOutcome o = run_on(map);
  expect_the_others_reach(o);
  const UgvOutcome& stuck = o.ugvs[0];
  EXPECT_FALSE(stuck.reached);
  EXPECT_GT(stuck.blocked_s, 20.0) << stuck.end;
  EXPECT_EQ(stuck.blocked_reason, msg::BlockedReason::kNotLocalised) << stuck.end;
  EXPECT_NE(stuck.end.find("not localised"), std::string::npos) << stuck.end;
}

// Walled in (a pen of 0.6 m walls 1 m around its start): localised, but no way out. It says
// so, the UAV stops serving it, the others go on; standing all along, it waited all along.
TEST(StuckUgv, AUgvWalledInIsBlockedWithNoPathAndWaitsTheWholeMission) {
  const double x = 0.0, y = 16.0, d = 1.0, t = 0.1, h = 0.6;
  const std::string map = map_with({{Vec2(x - d, y), Vec2(t, d + t), h},
                                    {Vec2(x + d, y), Vec2(t, d + t), h},
                                    {Vec2(x, y - d), Vec2(d + t, t), h},
                                    {Vec2(x, y + d), Vec2(d + t, t), h}},
                                   "pen");
  const MissionOutcome o = run_on(map);
  expect_the_others_reach(o);
  const UgvOutcome& stuck = o.ugvs[0];
  EXPECT_FALSE(stuck.reached);
  EXPECT_FALSE(stuck.collided);
  EXPECT_GT(stuck.blocked_s, 20.0) << stuck.end;
  EXPECT_EQ(stuck.blocked_reason, msg::BlockedReason::kNoPath) << stuck.end;
  EXPECT_NE(stuck.end.find("no path"), std::string::npos) << stuck.end;
  // It barely moved, so nearly all of the mission was waiting.
  EXPECT_GT(stuck.waiting_time_s, 0.8 * o.sim_time_s);
  EXPECT_GT(o.max_waiting_time_s, 0.8 * o.sim_time_s);
}
