// The boards' ROS 2 bridges over real DDS: a ROS 2 peer (Cyclone here; Fast DDS in SITL) reads
// a UGV's odometry, sends goals that the task validates, and the bridge's step on the task's
// thread allocates nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "allocation_counter.hpp"
#include "colag/hal/dds/device_participant.hpp"
#include "colag/hal/dds/take_one.hpp"
#include "colag/hal/ros2/ros2_names.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/ugv/app/ugv_ros2_bridge.hpp"
#include "dds_test_env.hpp"
#include "ros2_msgs.h"

namespace colag {
namespace {

using namespace std::chrono_literals;

struct UgvRig {
  UgvRig() {
    test::confine_dds_to_loopback();  // before the first participant (qemu has no multicast)
    config.id = 7;
    config.goal = Vec2(0.0, -10.0);
    task = std::make_unique<ugv::UgvNavTask>(config, bus, odo, drive);
    bridge = std::make_unique<ugv::UgvRos2Bridge>(*task);
  }
  ugv::UgvNavConfig config;
  platform::LoopbackTransport bus{1};
  hal::scripted::ScriptedWheelOdometry odo;
  hal::scripted::RecordingDrive drive;
  std::unique_ptr<ugv::UgvNavTask> task;
  std::unique_ptr<ugv::UgvRos2Bridge> bridge;
};

geometry_msgs_msg_dds__PoseStamped_ goal(double x, double y, const char* frame) {
  geometry_msgs_msg_dds__PoseStamped_ g{};
  g.header.frame_id = const_cast<char*>(frame);  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  g.pose.position = {x, y, 0.0};
  g.pose.orientation.w = 1.0;
  return g;
}

// Steps the bridge (10 Hz) until `done`, up to `limit` of wall time.
template <class Done>
bool step_until(ugv::UgvRos2Bridge& b, TimePoint& now, Done&& done, std::chrono::seconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    now += 100ms;
    b.step(now);
    if (done()) return true;
    std::this_thread::sleep_for(20ms);
  }
  return false;
}

// Starts the rig's bridge on a private domain and a ROS 2 peer's reliable writer on its
// `topic` (as RViz2 and `ros2 topic pub` publish).
struct BridgeAndTool {
  BridgeAndTool(UgvRig& rig, const char* topic, const dds_topic_descriptor_t& type) {
    const std::uint32_t domain = test::private_domain_id();
    board::Ros2Config cfg;
    cfg.enabled = true;
    std::string error;
    started = rig.bridge->start(domain, cfg, {}, error);
    EXPECT_TRUE(started) << error;
    EXPECT_TRUE(tool.init(domain));
    writer = tool.writer(hal::ros2::ros2_dds_topic("ugv7", topic), type,
                         {.reliable = true, .depth = 10});
    EXPECT_GT(writer, 0) << tool.last_error();
    // Matched with the bridge's reader before anything is sent: a reliable sample is then
    // delivered once (tests that count must not send twice).
    const auto end = std::chrono::steady_clock::now() + 10s;
    dds_publication_matched_status_t m{};
    while (writer > 0 && m.current_count == 0 && std::chrono::steady_clock::now() < end) {
      (void)dds_get_publication_matched_status(writer, &m);
      std::this_thread::sleep_for(10ms);
    }
    matched = m.current_count > 0;
    EXPECT_TRUE(matched);
  }
  bool ok() const { return started && writer > 0 && matched; }
  hal::dds::DeviceParticipant tool;
  dds_entity_t writer = 0;
  bool started = false, matched = false;
};

TEST(UgvRos2Bridge, GoalsFromRos2AreValidatedByTheTaskAndAnswered) {
  UgvRig rig;
  BridgeAndTool peer(rig, "goal_pose", geometry_msgs_msg_dds__PoseStamped__desc);
  ASSERT_TRUE(peer.ok());
  const dds_entity_t w = peer.writer;
  TimePoint now{};
  // A goal in another frame: refused, the goal unchanged.
  const auto odom_goal = goal(3.0, 4.0, "odom");
  ASSERT_TRUE(step_until(
      *rig.bridge, now,
      [&] {
        (void)dds_write(w, &odom_goal);
        return rig.bridge->counters().goals_refused > 0;
      },
      10s));
  EXPECT_EQ(rig.task->goal(), Vec2(0.0, -10.0));
  // Beyond the largest site (limits::kMaxSiteHalf_m): refused by the task.
  const auto far_goal = goal(20000.0, 0.0, "map");
  const std::uint64_t refused = rig.bridge->counters().goals_refused;
  ASSERT_TRUE(step_until(
      *rig.bridge, now,
      [&] {
        (void)dds_write(w, &far_goal);
        return rig.bridge->counters().goals_refused > refused;
      },
      10s));
  EXPECT_EQ(rig.task->goal(), Vec2(0.0, -10.0));
  // In the map: taken.
  const auto good = goal(3.0, 4.0, "map");
  ASSERT_TRUE(step_until(
      *rig.bridge, now,
      [&] {
        (void)dds_write(w, &good);
        return rig.task->goal() == Vec2(3.0, 4.0);
      },
      10s));
}

// Commands are applied in the order sent; a refusal (resume without a pause, an unknown
// command, return before it knows its start) changes nothing and is counted.
TEST(UgvRos2Bridge, CommandsFromRos2AreAppliedInOrderOrRefused) {
  UgvRig rig;
  BridgeAndTool peer(rig, "command", colag_msgs_msg_dds__UgvCommand__desc);
  ASSERT_TRUE(peer.ok());
  const dds_entity_t w = peer.writer;
  TimePoint now{};
  std::uint32_t next_id = 0;
  // Sends `command` once, and waits until the bridge has taken it.
  auto send = [&](std::uint8_t command) {
    colag_msgs_msg_dds__UgvCommand_ c{};
    c.header.frame_id = const_cast<char*>("");  // NOLINT(cppcoreguidelines-pro-type-const-cast)
    c.id = ++next_id;
    c.command = command;
    const std::uint64_t before = rig.bridge->counters().commands;
    return dds_write(w, &c) == DDS_RETCODE_OK &&
           step_until(
               *rig.bridge, now, [&] { return rig.bridge->counters().commands > before; }, 10s);
  };
  auto until = [&](auto done) { return step_until(*rig.bridge, now, done, 5s); };
  ASSERT_TRUE(send(1));  // pause
  EXPECT_TRUE(until([&] { return rig.task->paused(); }));
  const std::uint64_t refused = rig.bridge->counters().commands_refused;
  ASSERT_TRUE(send(2));  // resume
  EXPECT_TRUE(until([&] { return !rig.task->paused(); }));
  ASSERT_TRUE(send(2));   // resume again: not paused
  ASSERT_TRUE(send(42));  // unknown
  ASSERT_TRUE(send(4));   // return: not localised, its start unknown
  EXPECT_TRUE(until([&] { return rig.bridge->counters().commands_refused == refused + 3; }))
      << rig.bridge->counters().commands_refused - refused;
  EXPECT_EQ(rig.task->goal(), Vec2(0.0, -10.0));
  EXPECT_FALSE(rig.task->paused());
  ASSERT_TRUE(send(3));  // abort
  EXPECT_TRUE(until([&] { return rig.task->aborted(); }));
}

// The step runs on the task's thread: a copy into the mailbox, nothing allocated (DDS runs on
// the bridge's own thread).
TEST(UgvRos2Bridge, StepAllocatesNothingOnTheTasksThread) {
  UgvRig rig;
  board::Ros2Config cfg;
  cfg.enabled = true;
  cfg.map_period_s = 0.1;  // the map copy every step
  cfg.status_period_s = 0.1;
  std::string error;
  ASSERT_TRUE(rig.bridge->start(test::private_domain_id(), cfg, {}, error)) << error;
  TimePoint now{};
  for (int i = 0; i < 5; ++i) {  // warm-up
    now += 100ms;
    rig.bridge->step(now);
  }
  test::AllocationCounter count(test::AllocationCounter::Threads::kThisOne);
  for (int i = 0; i < 30; ++i) {
    now += 100ms;
    rig.bridge->step(now);
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_EQ(count.count(), 0U);
}

}  // namespace
}  // namespace colag
