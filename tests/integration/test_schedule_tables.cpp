// One schedule table per robot: the board programs (ugv_fw, uav_fw; SITL is the same programs
// on the simulated devices) and the lock-step mission (colag_sim) build their executor tables
// from UgvSchedule and UavSchedule, and nothing else.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "colag/sim/mission/mission.hpp"
#include "colag/uav/app/uav_board.hpp"
#include "colag/ugv/app/ugv_board.hpp"
#include "dds_test_env.hpp"

namespace colag {
namespace {

struct Row {
  std::string name;
  platform::LoopTiming timing;
  int lane;
};

std::vector<Row> rows_of(const platform::Schedule& table) {
  std::vector<Row> rows;
  for (std::size_t i = 0; i < table.size(); ++i) {
    const platform::TaskEntry& e = table.entry(i);
    rows.push_back({e.task->name(), {e.period, e.budget, e.offset}, e.lane});
  }
  return rows;
}

void expect_row(const Row& row, const char* name, const platform::LoopTiming& t, int lane) {
  EXPECT_EQ(row.name, name);
  EXPECT_EQ(row.timing.period, t.period) << name;
  EXPECT_EQ(row.timing.budget, t.budget) << name;
  EXPECT_EQ(row.timing.offset, t.offset) << name;
  EXPECT_EQ(row.lane, lane) << name;
}

class ScheduleTables : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { test::confine_dds_to_loopback(); }
};

TEST_F(ScheduleTables, TheUgvBoardProgramRunsTheUgvTable) {
  ugv::UgvBoardConfig cfg;
  cfg.can_interface = "sim";  // SITL's CAN bus: no interface needed to build the program
  cfg.common.dds_domain = test::private_domain_id();
  auto board = std::make_unique<ugv::UgvBoard>(cfg, 1.0);
  std::string error;
  ASSERT_TRUE(board->start(error)) << error;
  const ugv::UgvSchedule table;
  const std::vector<Row> rows = rows_of(board->schedule());
  ASSERT_EQ(rows.size(), 3u);
  expect_row(rows[0], "transport", table.transport, 0);
  expect_row(rows[1], "ugv_control", table.control, 0);
  expect_row(rows[2], "ugv_planning", table.planning, 0);
  EXPECT_TRUE(board->stop_motors());
}

TEST_F(ScheduleTables, TheUavBoardProgramRunsTheUavTable) {
  uav::UavBoardConfig cfg;
  cfg.sim_hal = true;
  cfg.common.dds_domain = test::private_domain_id();
  auto board = std::make_unique<uav::UavBoard>(cfg, 1.0);
  std::string error;
  ASSERT_TRUE(board->start(error)) << error;
  const uav::UavSchedule table;
  const std::vector<Row> rows = rows_of(board->schedule());
  ASSERT_EQ(rows.size(), 5u);
  expect_row(rows[0], "transport", table.transport, 0);
  expect_row(rows[1], "uav_control", table.control, 0);
  expect_row(rows[2], "uav_mapping", table.mapping, 0);
  expect_row(rows[3], "uav_sharing", table.sharing, 0);
  expect_row(rows[4], "uav_scheduling", table.scheduling, 0);
}

TEST_F(ScheduleTables, TheLockstepMissionRunsEachRobotFromItsTableInItsLane) {
  mission::MissionConfig cfg;
  cfg.scenario = "sparse";
  cfg.ugvs = 2;
  std::string error;
  const std::unique_ptr<mission::Mission> m = mission::Mission::compose(cfg, error);
  ASSERT_TRUE(m) << error;
  const ugv::UgvSchedule ugv_table;
  const uav::UavSchedule uav_table;
  // The simulation's own rows (the shared network, the world, the ground truth's watch of who
  // stands still: lane 0, run first), then the robots': the UAV's in lane 1, each UGV's in a
  // lane of its own, all of them side by side.
  const std::vector<Row> rows = rows_of(m->executor().schedule());
  ASSERT_EQ(rows.size(), 3u + 4u + 2u * 2u);
  expect_row(rows[0], "transport", {std::chrono::milliseconds(10), std::chrono::milliseconds(2)},
             0);
  EXPECT_EQ(rows[1].name, "world");
  EXPECT_EQ(rows[1].lane, 0);
  EXPECT_EQ(rows[2].name, "still_watch");
  EXPECT_EQ(rows[2].lane, 0);
  expect_row(rows[3], "uav_control", uav_table.control, 1);
  expect_row(rows[4], "uav_mapping", uav_table.mapping, 1);
  expect_row(rows[5], "uav_sharing", uav_table.sharing, 1);
  expect_row(rows[6], "uav_scheduling", uav_table.scheduling, 1);
  for (int i = 0; i < 2; ++i) {
    expect_row(rows[7 + 2 * i], "ugv_control", ugv_table.control, i + 2);
    expect_row(rows[8 + 2 * i], "ugv_planning", ugv_table.planning, i + 2);
  }
}

}  // namespace
}  // namespace colag
