// A UGV's firmware process dies mid-mission and starts again (FaultConfig::kill_ugv, what
// `scripts/sitl.sh --kill-ugv I@T --restart-after S` does with ugv_fw): the new process knows
// only its configuration, must be found and localised again, and must finish. Field world.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "colag/msg/map_patch.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/readers.hpp"
#include "colag/sim/mission/mission.hpp"
#include "colag/sim/mission/reboot_link.hpp"
#include "colag/sim/mission/world_file.hpp"
#include "colag/ugv/waiting.hpp"

using namespace colag;
using namespace colag::mission;

namespace {

// Dense, 5 UGVs, seed 1, field world: UGV 2's process dies at 30 s (it is driving, 11 m from
// where its mission starts) and starts again 5 s later.
MissionConfig ugv_2_restarted() {
  MissionConfig cfg;
  cfg.scenario = "dense";
  cfg.ugvs = 5;
  cfg.seed = 1;
  cfg.max_time_s = 250;
  cfg.faults.kill_ugv = 2;
  cfg.faults.kill_ugv_at_s = 30.0;
  cfg.faults.restart_after_s = 5.0;
  std::string error;
  EXPECT_TRUE(world_from_name("field", cfg.world, error)) << error;
  return cfg;
}

MissionOutcome fly(const MissionConfig& cfg) {
  std::string error;
  const std::unique_ptr<Mission> m = Mission::compose(cfg, error);
  EXPECT_TRUE(m) << error;
  if (!m) return {};
  m->fly();
  return m->collect();
}

double part(const UgvOutcome& u, ugv::WaitPart p) {
  return u.waiting_parts[static_cast<std::size_t>(p)];
}

}  // namespace

TEST(RebootLink, ANewProcessTakesTheDeadOnesSubscriptionsOver) {
  platform::LoopbackTransport bus(1);
  platform::Transport& uav = bus.port(0);
  RebootLink link(bus.port(1));
  msg::MapPatch patch;
  patch.ugv_id = 1;
  const auto deliver = [&] {
    EXPECT_TRUE(uav.publish(patch));
    bus.poll(TimePoint{} + std::chrono::seconds(1));
  };
  {
    platform::QueueReader<msg::MapPatch> first;
    ASSERT_TRUE(first.attach(link, 1));
    deliver();
    EXPECT_EQ(first.received(), 1u);
    link.kill();
    deliver();  // nobody listens: lost
    EXPECT_EQ(first.received(), 1u);
    EXPECT_FALSE(link.publish(patch));  // a dead process sends nothing
  }  // the dead process's reader is gone: nothing may reach it any more
  deliver();
  link.start();
  platform::QueueReader<msg::MapPatch> second;
  ASSERT_TRUE(second.attach(link, 1));
  EXPECT_EQ(link.relays(), 1u);  // the bus saw one subscription in all
  deliver();
  EXPECT_EQ(second.received(), 1u);
  EXPECT_TRUE(link.publish(patch));
}

// The UAV looks for the restarted UGV where it last knew it, not where the new process asks
// (its mission's start, 11 m away): localised again within 2.2 s of the restart; the old way,
// flying to the start first, took 19.2 s in this mission.
TEST(UgvRestart, ARestartedUgvIsFoundWhereItStoodAndFinishes) {
  const MissionOutcome o = fly(ugv_2_restarted());
  EXPECT_TRUE(o.all_reached);
  EXPECT_EQ(o.collisions, 0);
  ASSERT_EQ(o.ugvs.size(), 5u);
  const UgvOutcome& u = o.ugvs[2];
  EXPECT_TRUE(u.reached);
  EXPECT_GT(u.min_clearance_m, 0.0);
  // Standing dead is a fault (the 5 s less the base's watchdog coasting it to a stop: 4.36 s);
  // waiting for its first relative pose, twice, is start-up: 1.4 s at the mission's start and
  // the rest after the restart.
  EXPECT_GT(part(u, ugv::WaitPart::kFault), 4.0);
  EXPECT_LE(part(u, ugv::WaitPart::kFault), 5.0);
  EXPECT_LT(part(u, ugv::WaitPart::kStartup), 6.0);
  // Every second it stood is in a part (the dead process's too).
  double parts = 0.0;
  for (double p : u.waiting_parts)
    parts += p;
  EXPECT_NEAR(parts, u.waiting_time_s, 1e-6);
  EXPECT_NEAR(u.waiting_time_s, u.stopped_s, 0.1 * static_cast<double>(u.stops) + 0.2);
  // The dead process's frozen estimate is not held against the truth.
  EXPECT_LT(u.nees_mean, 6.0);
}

// Killed and never started again: it stands where its base stopped it; the others finish and
// the mission ends without waiting for it.
TEST(UgvRestart, AUgvThatNeverComesBackStandsAndTheOthersFinish) {
  MissionConfig cfg = ugv_2_restarted();
  cfg.faults.restart_after_s = -1.0;
  const MissionOutcome o = fly(cfg);
  ASSERT_EQ(o.ugvs.size(), 5u);
  EXPECT_EQ(o.collisions, 0);
  EXPECT_FALSE(o.ugvs[2].reached);
  EXPECT_LT(o.sim_time_s, cfg.max_time_s);
  for (int i : {0, 1, 3, 4})
    EXPECT_TRUE(o.ugvs[static_cast<std::size_t>(i)].reached) << "UGV " << i;
  EXPECT_GT(part(o.ugvs[2], ugv::WaitPart::kFault), o.sim_time_s - 31.0);
}

TEST(UgvRestart, BadKillsAreRefused) {
  MissionConfig cfg;
  cfg.ugvs = 3;
  std::string error;
  cfg.faults.restart_after_s = 5.0;  // nothing killed
  EXPECT_FALSE(check(cfg, error));
  EXPECT_NE(error.find("--restart-after"), std::string::npos) << error;
  cfg.faults.kill_ugv = 3;  // there are three: 0..2
  cfg.faults.kill_ugv_at_s = 10.0;
  EXPECT_FALSE(check(cfg, error));
  EXPECT_NE(error.find("--kill-ugv 3"), std::string::npos) << error;
  cfg.faults.kill_ugv = 2;
  EXPECT_TRUE(check(cfg, error)) << error;
  int id = -1;
  double at = -1.0;
  EXPECT_TRUE(parse_kill("2@30.5", id, at));
  EXPECT_EQ(id, 2);
  EXPECT_DOUBLE_EQ(at, 30.5);
  for (const char* bad : {"", "2", "@30", "2@", "2@0", "-1@3", "x@3", "2@3s", "2@nan"})
    EXPECT_FALSE(parse_kill(bad, id, at)) << bad;
}
