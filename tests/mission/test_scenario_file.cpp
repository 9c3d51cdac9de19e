// Scenario files (sim/mission/scenario_file.hpp): the shipped ones load; a mission flies the
// starts and goals a file gives; a mistake is refused with the key and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "colag/sim/mission/mission.hpp"
#include "colag/sim/mission/scenario_file.hpp"
#include "temp_file.hpp"

using namespace colag;
using namespace colag::mission;

namespace {
std::string refusal(const std::string& text) {
  MissionConfig cfg;
  std::string error;
  EXPECT_FALSE(load_scenario_file(test::write_temp_file("scenario.yaml", text), cfg, error))
      << text;
  return error;
}
}  // namespace

TEST(ScenarioFile, EveryShippedScenarioLoads) {
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(COLAG_CONFIG_DIR "/scenarios")) {
    if (e.path().extension() != ".yaml") continue;
    ++files;
    MissionConfig cfg;
    std::string error;
    EXPECT_TRUE(load_scenario_file(e.path().string(), cfg, error)) << error;
    EXPECT_EQ(cfg.placements.size(), static_cast<std::size_t>(cfg.ugvs)) << e.path();
    EXPECT_TRUE(check(cfg, error)) << e.path() << ": " << error;
  }
  EXPECT_GE(files, 3);
}

TEST(ScenarioFile, ASiteSizesTheGeneratorAndACountLaysTheUgvsOutAlongIt) {
  MissionConfig cfg;
  std::string error;
  ASSERT_TRUE(load_scenario_file(
      test::write_temp_file("site.yaml", "map: {generator: sparse, site: [100, 60]}\nugvs: 4\n"),
      cfg, error))
      << error;
  EXPECT_EQ(cfg.site, Vec2(100.0, 60.0));
  ASSERT_EQ(cfg.placements.size(), 4u);
  for (int i = 0; i < 4; ++i) {  // 25 m apart, 2.5 m inside the north and south edges
    EXPECT_EQ(cfg.placements[i].start.p, Vec2(-37.5 + 25.0 * i, 27.5));
    EXPECT_EQ(cfg.placements[i].goal, Vec2(-37.5 + 25.0 * i, -27.5));
  }
  EXPECT_EQ(cfg.uav_start, Vec3(0.0, 26.5, 1.0));
  sim::BoxWorld world;
  ASSERT_TRUE(build_world(cfg, world, error)) << error;
  // The sparse field's density (40 boxes per 27 x 27 m) over 100 x 50 m: 274 boxes.
  EXPECT_EQ(world.boxes.size(), 274u);
  EXPECT_DOUBLE_EQ(world.max_x_m, 50.0);
  EXPECT_DOUBLE_EQ(world.min_y_m, -25.0);
  // Mistakes.
  EXPECT_NE(
      refusal("map: {generator: dense}\nugvs: 4\n").find("ugvs: a number of UGVs needs map.site"),
      std::string::npos);
  EXPECT_NE(refusal("map: {pcd: a.pcd, site: [50, 50]}\nugvs: 2\n")
                .find("map.site: sizes a generated map"),
            std::string::npos);
  EXPECT_NE(
      refusal("map: {generator: dense, site: [20, 50]}\nugvs: 11\n").find("too narrow for 11 UGVs"),
      std::string::npos);
  EXPECT_NE(refusal("map: {generator: dense, site: [5, 50]}\nugvs: 1\n").find("map.site: expected"),
            std::string::npos);
}

TEST(ScenarioFile, TheMissionFliesTheFilesStartsAndGoals) {
  MissionConfig cfg;
  cfg.max_time_s = 200;
  std::string error;
  ASSERT_TRUE(load_scenario_file(COLAG_CONFIG_DIR "/scenarios/crossing.yaml", cfg, error)) << error;
  ASSERT_EQ(cfg.ugvs, 4);
  EXPECT_EQ(cfg.scenario, "dense");
  EXPECT_EQ(cfg.world.name, "field");
  const std::unique_ptr<Mission> m = Mission::compose(cfg, error);
  ASSERT_TRUE(m) << error;
  // Where the world put each UGV, and where its firmware was told to go.
  EXPECT_LT((m->world().ugv(2).pose().p - Vec2(16, 3)).norm(), 1e-9);
  EXPECT_NEAR(std::abs(m->world().ugv(2).pose().yaw_rad), M_PI, 1e-9);
  m->fly();
  const MissionOutcome o = m->collect();
  EXPECT_EQ(o.collisions, 0);
  EXPECT_TRUE(o.all_reached);
  for (const UgvOutcome& u : o.ugvs)
    EXPECT_LT(u.goal_distance_m, cfg.goal_tolerance_m);
  // The two westbound UGVs drove ~32 m along x.
  EXPECT_GT(o.ugvs[3].traj_length_m, 30.0);
}

TEST(ScenarioFile, MistakesAreRefusedNamingTheKey) {
  const std::string dense = "map: {generator: dense}\n";
  const std::string one = "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16]}\n";
  EXPECT_NE(refusal(one).find("map: required"), std::string::npos);
  EXPECT_NE(refusal(dense).find("ugvs: required"), std::string::npos);
  EXPECT_NE(refusal(dense + one + "ugvz: 1\n").find("ugvz: unknown key"), std::string::npos);
  EXPECT_NE(refusal("map: {generator: dense, pcd: a.pcd}\n" + one).find("map: give either"),
            std::string::npos);
  EXPECT_NE(refusal("map: {generator: hills}\n" + one).find("map.generator"), std::string::npos);
  EXPECT_NE(refusal("map: {pcd: a.pcd, units: mm}\n" + one).find("map.units"), std::string::npos);
  EXPECT_NE(refusal(dense + "ugvs:\n  - {start: [0, 16], goal: [0, -16]}\n")
                .find("ugvs[0].start: expected a list of 3 numbers"),
            std::string::npos);
  EXPECT_NE(refusal(dense + "ugvs:\n  - {start: [0, 16, 0], goal: [0, -30000]}\n")
                .find("ugvs[0].goal: (0.0, -30000.0) is beyond the largest site"),
            std::string::npos);
  EXPECT_NE(refusal(dense + one + "  - {start: [0.5, 16, -90], goal: [2, -16]}\n")
                .find("ugvs[1].start: 0.50 m from ugvs[0].start"),
            std::string::npos);
  EXPECT_NE(refusal(dense + "ugvs: []\n").find("ugvs: expected a list of 1.."), std::string::npos);
  EXPECT_NE(refusal(dense + one + "uav: {start: [0, 0, 50]}\n").find("uav.start"),
            std::string::npos);
  EXPECT_NE(refusal(dense + one + "faults: {loss_percent: 120}\n").find("faults.loss_percent"),
            std::string::npos);
  EXPECT_NE(refusal(dense + one + "world: nowhere.yaml\n").find("world: "), std::string::npos);
  EXPECT_NE(refusal("- 1\n").find("expected a mapping"), std::string::npos);
  // A generator's parameters: only its own, in range.
  EXPECT_NE(refusal("map: {generator: dense, rooms: [2, 2]}\n" + one).find("map.rooms: not a"),
            std::string::npos);
  EXPECT_NE(refusal("map: {generator: rooms, boxes: 10}\n" + one).find("map.boxes: not a"),
            std::string::npos);
  EXPECT_NE(refusal("map: {generator: rooms, rooms: [2.5, 2]}\n" + one).find("map.rooms"),
            std::string::npos);
  EXPECT_NE(refusal("map: {generator: rooms, door_m: 0.5}\n" + one).find("map.door_m"),
            std::string::npos);
  EXPECT_NE(refusal("map: {generator: sparse, boxes: 0}\n" + one).find("map.boxes"),
            std::string::npos);
  EXPECT_NE(refusal(dense + one + "faults: {uav_blackout: [40, 20]}\n")
                .find("faults.uav_blackout: expected [from_s, to_s]"),
            std::string::npos);
  EXPECT_NE(refusal(dense + one + "faults: {blackout: 20}\n").find("faults.blackout"),
            std::string::npos);
}

TEST(ScenarioFile, FaultWindowsAndWheelBiasReachTheMission) {
  MissionConfig cfg;
  std::string error;
  ASSERT_TRUE(load_scenario_file(
      test::write_temp_file(
          "faults.yaml",
          "map: {generator: dense}\nugvs:\n  - {start: [0, 16, -90], goal: [0, -16]}\n"
          "faults: {blackout: [10, 12], uav_blackout: [20, 30.5], rpe_blackout: [40, 60],\n"
          "         odom_bias_percent: -3}\n"),
      cfg, error))
      << error;
  EXPECT_DOUBLE_EQ(cfg.faults.blackout.from_s, 10.0);
  EXPECT_DOUBLE_EQ(cfg.faults.blackout.to_s, 12.0);
  EXPECT_DOUBLE_EQ(cfg.faults.uav_blackout.to_s, 30.5);
  EXPECT_DOUBLE_EQ(cfg.faults.rpe_blackout.from_s, 40.0);
  EXPECT_DOUBLE_EQ(cfg.faults.odom_bias, -0.03);
  EXPECT_TRUE(check(cfg, error)) << error;
}

TEST(ScenarioFile, SeveralUavsAndTheLossOfOneReachTheMission) {
  MissionConfig cfg;
  std::string error;
  ASSERT_TRUE(
      load_scenario_file(test::write_temp_file("uavs.yaml",
                                               "map: {generator: dense}\nuav: {count: 3}\n"
                                               "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16]}\n"
                                               "faults: {uav_lost_at_s: 42, uav_lost_id: 0,\n"
                                               "  kill_ugv: 0, kill_ugv_at_s: 30,\n"
                                               "  restart_after_s: 5}\n"),
                         cfg, error))
      << error;
  EXPECT_EQ(cfg.uavs, 3);
  EXPECT_DOUBLE_EQ(cfg.faults.uav_lost_at_s, 42.0);
  EXPECT_EQ(cfg.faults.uav_lost_id, 0);
  EXPECT_EQ(cfg.faults.kill_ugv, 0);
  EXPECT_DOUBLE_EQ(cfg.faults.kill_ugv_at_s, 30.0);
  EXPECT_DOUBLE_EQ(cfg.faults.restart_after_s, 5.0);
  EXPECT_FALSE(load_scenario_file(
      test::write_temp_file("uavs9.yaml",
                            "map: {generator: dense}\nuav: {count: 9}\n"
                            "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16]}\n"),
      cfg, error));
  EXPECT_NE(error.find("uav.count"), std::string::npos) << error;
}

TEST(ScenarioFile, GeneratorParametersReachTheMap) {
  const std::string one = "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16]}\n";
  MissionConfig cfg;
  std::string error;
  ASSERT_TRUE(load_scenario_file(
      test::write_temp_file(
          "rooms.yaml", "map: {generator: rooms, rooms: [2, 4], door_m: 2, furniture: 5}\n" + one),
      cfg, error))
      << error;
  sim::BoxWorld world;
  ASSERT_TRUE(build_world(cfg, world, error)) << error;
  // 2 x 4 rooms: 1 x 4 + 3 x 2 wall segments, each two pieces; and 5 pieces of furniture.
  EXPECT_EQ(world.boxes.size(), 2u * 10u + 5u);
  cfg = MissionConfig{};
  ASSERT_TRUE(load_scenario_file(
      test::write_temp_file("boxes.yaml", "map: {generator: sparse, boxes: 12}\n" + one), cfg,
      error))
      << error;
  ASSERT_TRUE(build_world(cfg, world, error)) << error;
  EXPECT_EQ(world.boxes.size(), 12u);
}

TEST(ScenarioFile, AUgvPassesItsRoutesPointsInOrderBeforeItsGoal) {
  // Straight from start to goal is 32 m; through the two points 46.7 m.
  MissionConfig cfg;
  std::string error;
  ASSERT_TRUE(load_scenario_file(test::write_temp_file("route.yaml", R"(map: {generator: sparse}
world: field
ugvs:
  - {start: [0, 16, -90], goal: [0, -16], via: [[8, 4], [-8, -4]]}
)"),
                                 cfg, error))
      << error;
  ASSERT_EQ(cfg.placements[0].via.size(), 2u);
  MissionTrace trace;
  auto o = run_mission(cfg, &trace, &error);
  ASSERT_TRUE(o) << error;
  EXPECT_TRUE(o.value().all_reached);
  EXPECT_EQ(o.value().collisions, 0);
  // Where the true path came closest to each point, and when: within the pass radius (1 m, by
  // the UGV's estimate) plus its error, the first before the second.
  const std::vector<Vec2> via = cfg.placements[0].via;
  std::vector<double> closest(via.size(), 1e9), when(via.size(), -1.0);
  for (const auto& s : trace.ugv_paths[0]) {
    for (std::size_t k = 0; k < via.size(); ++k) {
      const double d = (s.truth - via[k]).norm();
      if (d < closest[k]) closest[k] = d, when[k] = s.t_s;
    }
  }
  EXPECT_LT(closest[0], 1.5);
  EXPECT_LT(closest[1], 1.5);
  EXPECT_LT(when[0], when[1]);
  const UgvOutcome& u = o.value().ugvs[0];
  EXPECT_GT(u.traj_length_m, 46.7 - 2 * 1.5 - u.goal_distance_m);
}

TEST(ScenarioFile, ARoutesMistakesAreRefusedNamingThePoint) {
  const std::string dense = "map: {generator: dense}\n";
  EXPECT_NE(
      refusal(dense + "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16], via: [[1, 2], [3]]}\n")
          .find("ugvs[0].via[1]: expected [x, y]"),
      std::string::npos);
  EXPECT_NE(refusal(dense + "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16], via: [[0, 40000]]}\n")
                .find("ugvs[0].via[0]: (0.0, 40000.0) is beyond the largest site"),
            std::string::npos);
  std::string many = "[";
  for (int i = 0; i < 17; ++i)
    many += std::string(i > 0 ? ", " : "") + "[0, " + std::to_string(i) + "]";
  EXPECT_NE(
      refusal(dense + "ugvs:\n  - {start: [0, 16, -90], goal: [0, -16], via: " + many + "]}\n")
          .find("ugvs[0].via: expected a list of at most 16"),
      std::string::npos);
}
