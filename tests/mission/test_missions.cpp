// Whole missions: the real firmware tasks against the simulated world (seeded, a few seconds
// each). What the paper's system must do, and what its ablation must fail to do.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "colag/common/limits.hpp"
#include "colag/sim/mission/mission.hpp"
#include "colag/sim/mission/world_file.hpp"

using namespace colag;
using namespace colag::mission;

namespace {

MissionOutcome run(const MissionConfig& cfg) {
  std::string error;
  auto out = run_mission(cfg, nullptr, &error);
  EXPECT_TRUE(out) << error;
  return out.value();
}

void expect_all_reached_safely(const MissionOutcome& o) {
  EXPECT_TRUE(o.all_reached);
  EXPECT_EQ(o.collisions, 0);
  for (const UgvOutcome& u : o.ugvs) {
    EXPECT_TRUE(u.reached) << "UGV " << u.id;
    EXPECT_FALSE(u.collided) << "UGV " << u.id;
    EXPECT_GT(u.min_clearance_m, 0.0) << "UGV " << u.id;
    // It really crossed: starts are 32 m from goals, so the path is at least 32 m less what is
    // left to the goal (triangle inequality; 1 cm for rounding).
    EXPECT_GE(u.traj_length_m, 32.0 - u.goal_distance_m - 0.01) << "UGV " << u.id;
    EXPECT_LE(u.goal_distance_m, 0.5) << "UGV " << u.id;
    EXPECT_EQ(u.end, "reached its goal") << "UGV " << u.id;
  }
  EXPECT_EQ(exit_code(o), 0);
}

}  // namespace

TEST(Mission, SparseThreeUgvsAllReachWithoutCollision) {
  MissionConfig cfg;
  cfg.scenario = "sparse";
  cfg.ugvs = 3;
  cfg.seed = 2;
  cfg.max_time_s = 200;
  const MissionOutcome o = run(cfg);
  expect_all_reached_safely(o);
  EXPECT_LT(o.reach_time_s, 150.0);
  EXPECT_GT(o.map_patches, 100u);
}

TEST(Mission, DenseFiveUgvsAllReachWithoutCollision) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 5;
  cfg.seed = 3;
  cfg.max_time_s = 250;
  const MissionOutcome o = run(cfg);
  expect_all_reached_safely(o);
  EXPECT_GT(o.uav_traj_length_m, 20.0);
  EXPECT_GT(o.schedules, 0u);
  for (const UgvOutcome& u : o.ugvs) {
    // The firmware's account of its stops adds up, and matches the truth to a few control
    // periods per stop (its wheel odometry lags the wheels by one CAN period), plus what it
    // creeps at the threshold: wheel odometry with 3 cm/s of noise cannot tell 5.5 cm/s (moving,
    // by the truth) from 4.5 cm/s (standing); a UGV crept at 5.5 cm/s for 0.4 s here.
    double parts = 0.0;
    for (double p : u.waiting_parts)
      parts += p;
    EXPECT_NEAR(parts, u.waiting_time_s, 1e-6) << "UGV " << u.id;
    // The support part, by what it called the UAV for, adds up too.
    double causes = 0.0;
    for (double c : u.support_causes)
      causes += c;
    EXPECT_NEAR(causes, u.waiting_parts[static_cast<std::size_t>(colag::ugv::WaitPart::kSupport)],
                1e-6)
        << "UGV " << u.id;
    EXPECT_NEAR(u.waiting_time_s, u.stopped_s, 0.1 * (u.stops + 1) + 0.5) << "UGV " << u.id;
    EXPECT_GT(u.stops, 0) << "UGV " << u.id;  // it did wait for the UAV at least at start
    // Its covariance is honest in the world whose noise it models (3 dof: 3 expected).
    EXPECT_GT(u.nees_samples, 100u) << "UGV " << u.id;
    EXPECT_GT(u.nees_mean, 1.0) << "UGV " << u.id;
    EXPECT_LT(u.nees_mean, 6.0) << "UGV " << u.id;
    // Each UGV receives what is meant for it (and the UAV's fleet topics), not everything the
    // UAV sends to the five of them: under half of it (it was all of it, and more, before).
    EXPECT_GT(u.bytes_in_per_s, 1000.0) << "UGV " << u.id;
    EXPECT_LT(u.bytes_in_per_s, 0.5 * o.uav_bytes_out_per_s) << "UGV " << u.id;
  }
}

TEST(Mission, ThirtyTwoUgvsAllReachAndEachReceivesAboutWhatOneOfThreeDoes) {
  // The largest fleet, in the paper's 40 m arena (a second row of lanes behind the first): every
  // UGV reaches without a collision, and what each one receives does not grow with the fleet
  // (only with how many others are near it, at most kMaxNearbyUgvs, and the farther ones at
  // half the rate): were every UAV sample delivered to every UGV, each would take in the UAV's
  // whole output, ten times the 3-UGV figure. Issue 23's bound: 1.2x (1.09x measured).
  MissionConfig cfg;
  cfg.scenario = "sparse";
  cfg.seed = 2;
  cfg.max_time_s = 400;
  cfg.ugvs = 3;
  const MissionOutcome three = run(cfg);
  expect_all_reached_safely(three);
  cfg.ugvs = static_cast<int>(limits::kMaxUgvs);
  const MissionOutcome all = run(cfg);
  expect_all_reached_safely(all);
  ASSERT_EQ(all.ugvs.size(), limits::kMaxUgvs);
  EXPECT_LT(all.bytes_in_per_ugv_per_s, 1.2 * three.bytes_in_per_ugv_per_s);  // issue 23
  EXPECT_GT(all.uav_bytes_out_per_s, 5.0 * three.uav_bytes_out_per_s);        // the UAV's does grow
}

TEST(Mission, ALongSiteIsCrossedWithMapsThatMoveWithTheRobots) {
  // A 24 x 90 m dense site (field world): the goals lie 62 m beyond the maps' first window
  // (40 m, limits.hpp), so the UGVs and the UAV get there only if their windows move with them.
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.site = Vec2(24.0, 90.0);
  cfg.ugvs = 2;
  cfg.seed = 1;
  cfg.max_time_s = 1500;
  std::string error;
  ASSERT_TRUE(world_from_name("field", cfg.world, error)) << error;
  lay_out_site(cfg);
  ASSERT_EQ(cfg.placements.size(), 2u);
  EXPECT_DOUBLE_EQ(cfg.placements[0].goal.y(), -42.5);
  const MissionOutcome o = run(cfg);
  // expect_all_reached_safely's 32 m: the paper's arena; here each drives 85 m.
  expect_all_reached_safely(o);
  for (const UgvOutcome& u : o.ugvs)
    EXPECT_GE(u.traj_length_m, 85.0 - u.goal_distance_m - 0.01) << "UGV " << u.id;
}

TEST(Mission, SelfPerceptionBaselineUgvsKeepClearOfEachOther) {
  // The baseline the tables compare against (each UGV its own LiDAR and true pose, no UAV): its
  // UGVs hear of each other as ColAG's do, relayed per UGV. Without the relay (UGVs heard of
  // each other only from a UAV) UGVs 0 and 2 drove into each other here at 20 s.
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 3;
  cfg.seed = 1;
  cfg.self_perception = true;
  cfg.max_time_s = 40;  // past the contact (the whole mission: colag_bench tables)
  std::string error;
  ASSERT_TRUE(world_from_name("field", cfg.world, error)) << error;
  const MissionOutcome o = run(cfg);
  EXPECT_EQ(o.collisions, 0);
  for (const UgvOutcome& u : o.ugvs) {
    EXPECT_FALSE(u.collided) << "UGV " << u.id;
    EXPECT_GT(u.min_clearance_m, 0.0) << "UGV " << u.id;
    EXPECT_GT(u.traj_length_m, 10.0) << "UGV " << u.id;  // they drove, not stood
  }
}

TEST(Mission, WithoutRelativePoseUpdatesTheBlindUgvsDoNotMakeIt) {
  // The paper's ablation: RPE only initialises the estimator. Wheel odometry alone drifts; the
  // UGVs either stop for good (our predictor sees the growing uncertainty) or collide.
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 3;
  cfg.seed = 1;
  cfg.ablation = Ablation::kNoRpe;
  cfg.max_time_s = 100;
  const MissionOutcome o = run(cfg);
  EXPECT_TRUE(!o.all_reached || o.collisions > 0);
  double waiting = 0;
  for (const UgvOutcome& u : o.ugvs)
    waiting += u.waiting_time_s;
  EXPECT_GT(waiting, 60.0);
}

TEST(Mission, LossyLateNetworkStillNoCollision) {
  // 30 % of every message lost and 300 ms late (issue 8's seeded case).
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 5;
  cfg.seed = 1;
  cfg.max_time_s = 250;
  cfg.faults.loss = 0.3;
  cfg.faults.latency_ms = 300;
  expect_all_reached_safely(run(cfg));
}

TEST(Mission, UavBlackoutStopsTheUgvsThenTheyGoOn) {
  // The UAV silent from 20 s to 40 s: without relative poses the UGVs' uncertainty grows until
  // their 3-sigma ellipses would touch the map, so they stop rather than drive blind, and all
  // reach once the UAV is back.
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 5;
  cfg.seed = 1;
  cfg.max_time_s = 250;
  cfg.faults.uav_blackout = {20.0, 40.0};
  const MissionOutcome o = run(cfg);
  expect_all_reached_safely(o);
  EXPECT_GT(o.max_waiting_time_s, 10.0);  // someone sat out most of the blackout
  EXPECT_GT(o.reach_time_s, 40.0);
}

TEST(Mission, EveryRobotSilentTheyKeepClearOfEachOtherAndGoOn) {
  // Every topic of every robot lost from 20 s to 30 s: no relative poses, no maps, no statuses.
  // Each UGV keeps the others as discs growing with their silence, and none touches anything.
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 5;
  cfg.seed = 2;
  cfg.max_time_s = 250;
  cfg.faults.blackout = {20.0, 30.0};
  const MissionOutcome o = run(cfg);
  expect_all_reached_safely(o);
  EXPECT_GT(o.max_waiting_time_s, 5.0);  // someone sat out most of the blackout
}

TEST(Mission, FaultWindowsAreValidated) {
  TimeWindow w;
  EXPECT_TRUE(parse_window("20:40", w));
  EXPECT_DOUBLE_EQ(w.from_s, 20.0);
  EXPECT_DOUBLE_EQ(w.to_s, 40.0);
  EXPECT_FALSE(parse_window("40:20", w));
  EXPECT_FALSE(parse_window("20", w));
  EXPECT_FALSE(parse_window("a:b", w));
  EXPECT_FALSE(parse_window("-1:5", w));
  MissionConfig cfg;
  cfg.faults.loss = 1.5;
  std::string error;
  EXPECT_FALSE(run_mission(cfg, nullptr, &error));
  EXPECT_NE(error.find("--loss"), std::string::npos);
}

TEST(Mission, SameSeedSameMissionBitForBit) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 2;
  cfg.seed = 7;
  cfg.max_time_s = 40;
  cfg.threads = 2;
  const std::string a = to_json(run(cfg), /*include_wall_time=*/false);
  const std::string b = to_json(run(cfg), false);
  EXPECT_EQ(a, b);
  cfg.threads = 1;  // the work split over cores changes nothing
  EXPECT_EQ(a, to_json(run(cfg), false));
  cfg.seed = 8;
  EXPECT_NE(a, to_json(run(cfg), false));
}

TEST(Mission, RejectsABadConfiguration) {
  MissionConfig cfg;
  std::string error;
  cfg.ugvs = 0;
  EXPECT_FALSE(run_mission(cfg, nullptr, &error));
  EXPECT_NE(error.find("ugvs"), std::string::npos);
  cfg.ugvs = 2;
  cfg.threads = 0;
  EXPECT_FALSE(run_mission(cfg, nullptr, &error));
  EXPECT_NE(error.find("threads"), std::string::npos);
  cfg.threads = 2;
  cfg.ugvs = 2;
  cfg.scenario = "file";
  cfg.map_file = "/nonexistent.pcd";
  EXPECT_FALSE(run_mission(cfg, nullptr, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
}

// A mission cut short by its time limit says so, and, for each UGV, how far from its goal it
// ended and what it was doing; colag_sim's exit code is then 1. One that ends with every UGV
// done does not blame the limit.
TEST(Mission, AUgvShortOfItsGoalSaysWhereAndWhy) {
  MissionConfig cfg;
  cfg.scenario = "sparse";
  cfg.ugvs = 1;
  cfg.max_time_s = 10;
  const MissionOutcome o = run(cfg);
  ASSERT_EQ(o.ugvs.size(), 1u);
  EXPECT_FALSE(o.ugvs[0].reached);
  EXPECT_TRUE(o.time_limit_reached);
  EXPECT_GT(o.ugvs[0].goal_distance_m, 20.0);
  EXPECT_NE(o.ugvs[0].end.find("when the time limit (10 s) ended the mission"), std::string::npos)
      << o.ugvs[0].end;
  EXPECT_NE(to_json(o).find("\"time_limit_reached\": true"), std::string::npos);
  EXPECT_EQ(exit_code(o), 1);

  cfg.max_time_s = 400;
  const MissionOutcome done = run(cfg);
  ASSERT_TRUE(done.all_reached);
  EXPECT_FALSE(done.time_limit_reached);
  EXPECT_LT(done.sim_time_s, 400.0);
}

// The default time limit: the arena's 400 s, longer on a site by its length and its UGVs per UAV.
TEST(Mission, DefaultTimeLimitGrowsWithTheSiteAndTheFleetPerUav) {
  MissionConfig cfg;
  cfg.ugvs = 16;
  EXPECT_EQ(default_max_time_s(cfg), 400.0);  // the arena, whatever the fleet
  cfg.site = Vec2(60.0, 37.0);                // a 32 m drive
  cfg.ugvs = 4;
  EXPECT_DOUBLE_EQ(default_max_time_s(cfg), 400.0);
  cfg.site = Vec2(200.0, 200.0);  // 195 m
  EXPECT_DOUBLE_EQ(default_max_time_s(cfg), 400.0 * 195.0 / 32.0);
  cfg.ugvs = 32;
  EXPECT_DOUBLE_EQ(default_max_time_s(cfg), 400.0 * 195.0 / 32.0 * 8.0);
  cfg.uavs = 4;
  EXPECT_DOUBLE_EQ(default_max_time_s(cfg), 400.0 * 195.0 / 32.0 * 2.0);
}

// Every board keeps its own clock. Clocks an hour apart change nothing: the UGVs learn fleet time
// (the UAV's) before they publish or fuse anything, so the mission is the same, bit for bit.
namespace {

// Dense, 3 UGVs, seed 4, 60 s with `uavs` UAVs: the JSON with every clock as UAV 0's and with
// each other robot's an hour off (but for the clock fields) is the same.
void expect_clocks_an_hour_apart_change_nothing(int uavs) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 3;
  cfg.uavs = uavs;
  cfg.seed = 4;
  cfg.max_time_s = 60;
  auto one = nlohmann::json::parse(to_json(run(cfg), false));
  cfg.clocks.offset_s = 3600.0;
  auto apart = nlohmann::json::parse(to_json(run(cfg), false));
  for (auto& u : apart["ugvs"]) {
    EXPECT_GE(u["clock_error_s"].get<double>(), 0.0);  // synchronised at the end
    EXPECT_LT(u["clock_error_s"].get<double>(), 0.05);
    u.erase("clock_steps");
    u.erase("clock_error_s");
  }
  apart.erase("clocks");
  EXPECT_EQ(one.dump(), apart.dump());
}

}  // namespace

TEST(Mission, ClocksAnHourApartFlyTheSameMissionAsOneClock) {
  expect_clocks_an_hour_apart_change_nothing(1);
}

// With two UAVs, UAV 1 keeps its own clock too (an hour off UAV 0's, fleet time): it learns fleet
// time from UAV 0 as the UGVs do and converts at its edges, so the mission is again the one of a
// single clock. Before, its odometry, relative poses and patches went out on its own clock, and
// the UGVs threw them away as an hour old (reach 112-125 s against 74-81 s on dense 7, seeds 1-3).
TEST(Mission, TwoUavsOnTheirOwnClocksFlyTheSameMissionAsOneClock) {
  expect_clocks_an_hour_apart_change_nothing(2);
}

// Crystals 50 ppm apart, and the UAV's clock jumps back 5 s mid-mission: the UGVs notice within a
// few exchanges, follow it, and nobody collides or stays behind.
TEST(Mission, DriftingClocksAndAStepOfTheUavsClockKeepEveryoneSafe) {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 4;
  cfg.seed = 5;
  cfg.max_time_s = 250;
  cfg.clocks.offset_s = 3600.0;
  cfg.clocks.drift_ppm = 50.0;
  cfg.clocks.step_at_s = 30.0;
  cfg.clocks.step_s = -5.0;
  const MissionOutcome o = run(cfg);
  expect_all_reached_safely(o);
  for (const UgvOutcome& u : o.ugvs) {
    EXPECT_EQ(u.clock_steps, 1u) << "UGV " << u.id;
    EXPECT_GE(u.clock_error_s, 0.0) << "UGV " << u.id;
  }
}

// The field world's pillars, 5 UGVs, seed 4: a UGV whose estimate drifted 0.22 m (2.4 sigma)
// stopped 0.10 m from a pillar its 3-sigma ellipse already overlapped, then crept on over the
// same cells (excused from blocking, and then from the distance rule too) into it. The rule
// now holds over excused cells.
TEST(Mission, FieldPillarsAUgvDoesNotCreepIntoAPillarItsEllipseOverlaps) {
  MissionConfig cfg;
  cfg.scenario = "pillars";
  cfg.ugvs = 5;
  cfg.seed = 4;
  cfg.max_time_s = 200;
  cfg.world = sim::field_world();
  const MissionOutcome o = run(cfg);
  expect_all_reached_safely(o);
}
