// The UAV's PX4 and ROS 2 drivers against colag_world's flight stack (PX4's agent, FAST-LIO,
// the Livox driver on their own wire formats), over Cyclone in one process: take-off through
// the offboard protocol, odometry and clouds in, and every way PX4 leaves the mission.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "allocation_counter.hpp"
#include "colag/hal/px4/px4_flight_controller.hpp"
#include "colag/hal/ros2/ros2_devices.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/sim/bridge/px4_stack_bridge.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "dds_test_env.hpp"

using namespace colag;
using namespace std::chrono_literals;
using hal::px4::Px4Release;
using State = hal::px4::OffboardSequencer::State;

namespace {

struct Rig {
  explicit Rig(Px4Release world_release = Px4Release::kV116,
               Px4Release firmware_release = Px4Release::kV116)
      : world(world_config(), boxes(), clock), bridge(world), odometry(clock), lidar(clock) {
    test::confine_dds_to_loopback();
    const std::uint32_t domain = test::private_domain_id();
    world.add_uav(Vec3(0, 0, 0.05));  // on the ground
    sim::Px4StackConfig sc;
    sc.dds_domain = domain;
    sc.release = world_release;
    std::string error;
    EXPECT_TRUE(bridge.init(sc, error)) << error;
    hal::px4::Px4DriverConfig pc;
    pc.dds_domain = domain;
    pc.release = firmware_release;
    EXPECT_TRUE(px4.init(pc, error)) << error;
    hal::ros2::Ros2OdometryConfig oc;
    oc.dds_domain = domain;
    EXPECT_TRUE(odometry.init(oc, error)) << error;
    hal::ros2::Ros2LidarConfig lc;
    lc.dds_domain = domain;
    EXPECT_TRUE(lidar.init(lc, error)) << error;
  }
  static sim::SimWorldConfig world_config() {
    sim::SimWorldConfig wc;
    wc.lidar.columns = 360;
    return wc;
  }
  static sim::BoxWorld boxes() {
    sim::BoxWorld b;
    b.boxes.push_back({Vec2(3, 0), Vec2(0.4, 0.4), 0.6});
    return b;
  }
  // 50 Hz of simulated time per round: the world, its flight stack, the firmware's drivers
  // (hovering at `target` while they fly it), a little wall time for DDS. Until `done` or 15 s.
  bool run_until(const std::function<bool()>& done, const Vec3& target = Vec3(0, 0, 1.5)) {
    const auto deadline = std::chrono::steady_clock::now() + 15s;
    while (std::chrono::steady_clock::now() < deadline) {
      clock.advance(20ms);
      world.step(clock.now(), 0.02);
      bridge.step(clock.now());
      std::this_thread::sleep_for(2ms);
      status = px4.update(clock.now());
      hal::FlightSetpoint sp;
      sp.stamp = clock.now();
      sp.position_m = target;
      if (flying) (void)px4.send_setpoint(sp);
      hal::UavState s;
      if (odometry.poll(s)) state = s;
      hal::LidarScanView scan;
      if (lidar.poll(scan)) returns = scan.points.size();
      if (done()) return true;
    }
    return false;
  }

  hal::scripted::ManualClock clock;
  sim::SimWorld world;
  sim::Px4StackBridge bridge;
  hal::px4::Px4FlightController px4;
  hal::ros2::Ros2Odometry odometry;
  hal::ros2::Ros2Lidar lidar;
  hal::FlightStatus status;
  hal::UavState state;
  std::size_t returns = 0;
  bool flying = true;
};

}  // namespace

TEST(Px4Stack, TakesOffThroughTheOffboardProtocolAndReadsOdometryAndClouds) {
  Rig rig;
  ASSERT_TRUE(rig.run_until([&] { return rig.px4.sequencer().state() == State::kInControl; }))
      << "state " << static_cast<int>(rig.px4.sequencer().state()) << " heard "
      << rig.px4.counters().statuses;
  EXPECT_EQ(rig.status.state, msg::UavFlight::kInControl);
  ASSERT_TRUE(rig.run_until([&] { return rig.world.uav().state().pose.p.z() > 1.3; }))
      << "z " << rig.world.uav().state().pose.p.z();
  // PX4 saw the protocol: a heartbeat stream, setpoints, DO_SET_MODE and ARM, each answered.
  const sim::Px4StackCounters& c = rig.bridge.counters();
  EXPECT_GT(c.heartbeats, 20u);
  EXPECT_EQ(rig.px4.counters().commands, 2u);
  EXPECT_EQ(rig.px4.counters().acks, 2u);
  EXPECT_TRUE(rig.bridge.vehicle().armed());
  // FAST-LIO's odometry and the Livox cloud arrive through the ROS 2 drivers.
  EXPECT_NEAR((rig.state.pose.p - rig.world.uav().state().pose.p).norm(), 0.0, 0.2);
  EXPECT_GT(rig.returns, 50u);
  EXPECT_EQ(rig.lidar.counters().malformed, 0u);
  // And PX4's own odometry, converted from NED.
  hal::UavState px4_state;
  ASSERT_TRUE(rig.run_until([&] { return rig.px4.poll(px4_state); }));
  EXPECT_NEAR((px4_state.pose.p - rig.world.uav().state().pose.p).norm(), 0.0, 0.2);
}

TEST(Px4Stack, SilenceAFailsafeOrAPilotEndsControlWithinASecond) {
  for (int fault = 0; fault < 2; ++fault) {
    Rig rig;
    ASSERT_TRUE(rig.run_until([&] { return rig.world.uav().state().pose.p.z() > 1.0; }));
    if (fault == 0) {
      rig.bridge.set_silent(true);
    } else {
      rig.bridge.fail_safe();
    }
    const TimePoint at = rig.clock.now();
    ASSERT_TRUE(rig.run_until([&] { return rig.status.state == msg::UavFlight::kLost; }));
    EXPECT_LE(rig.clock.now() - at, 1s);
    EXPECT_EQ(rig.status.fault,
              fault == 0 ? msg::FlightFault::kSilent : msg::FlightFault::kFailsafe);
    // No more offboard stream: PX4's own failsafe has the aircraft. A heartbeat the writer
    // thread took before the loss may still reach DDS just after it (a slow board: CI's
    // emulated aarch64 was one), so count from a fifth of a second on.
    const TimePoint lost = rig.clock.now();
    ASSERT_TRUE(rig.run_until([&] { return rig.clock.now() - lost > 200ms; }));
    const auto heartbeats = rig.px4.counters().heartbeats;
    ASSERT_TRUE(rig.run_until([&] { return rig.clock.now() - lost > 1200ms; }));
    EXPECT_EQ(rig.px4.counters().heartbeats, heartbeats);
  }
}

TEST(Px4Stack, TheFirmwareStoppingItsStreamMakesPx4FailSafeAndHold) {
  Rig rig;
  ASSERT_TRUE(rig.run_until([&] { return rig.world.uav().state().pose.p.z() > 1.0; }));
  rig.flying = false;  // the supervisor stops sending setpoints (it lost its odometry, say)
  ASSERT_TRUE(rig.run_until([&] { return rig.bridge.vehicle().failsafe(); }));
  // PX4 holds, and the driver reports it left offboard... through the failsafe it sees.
  ASSERT_TRUE(rig.run_until([&] { return rig.status.state == msg::UavFlight::kLost; }));
  EXPECT_EQ(rig.status.fault, msg::FlightFault::kFailsafe);
}

TEST(Px4Stack, LandsAtTheEndAndPx4DisarmsOnTheGround) {
  Rig rig;
  ASSERT_TRUE(rig.run_until([&] { return rig.world.uav().state().pose.p.z() > 1.3; }));
  rig.flying = false;
  rig.px4.land(rig.clock.now());
  ASSERT_TRUE(rig.run_until([&] { return rig.px4.sequencer().state() == State::kLanded; }))
      << "z " << rig.world.uav().state().pose.p.z();
  EXPECT_FALSE(rig.bridge.vehicle().armed());
  EXPECT_LT(rig.world.uav().state().pose.p.z(), 0.2);
  EXPECT_EQ(rig.status.state, msg::UavFlight::kLanding);
}

TEST(Px4Stack, AReleaseMismatchIsReportedByName) {
  Rig rig(Px4Release::kV115, Px4Release::kV116);
  ASSERT_TRUE(rig.run_until([&] { return rig.status.fault == msg::FlightFault::kWrongRelease; }))
      << "fault " << static_cast<int>(rig.status.fault);
  EXPECT_EQ(rig.status.state, msg::UavFlight::kStarting);
  EXPECT_NE(rig.px4.diagnosis().find("rt/fmu/out/vehicle_status (release 1.15)"), std::string::npos)
      << rig.px4.diagnosis();
  EXPECT_EQ(rig.px4.counters().commands, 0u);  // it never asks a PX4 it does not understand
}

TEST(Px4Stack, PointsToPx4V115WhenConfiguredSo) {
  Rig rig(Px4Release::kV115, Px4Release::kV115);
  ASSERT_TRUE(rig.run_until([&] { return rig.px4.sequencer().state() == State::kInControl; }));
}

// The flight controller's path at the control rate (status, acks and odometry in; heartbeat and
// setpoint out) allocates nothing on the task's thread once in control (Cyclone's own threads
// allocate by design).
TEST(Px4Stack, InControlTheDriverAllocatesNothingOnTheTasksThread) {
  Rig rig;
  ASSERT_TRUE(rig.run_until([&] { return rig.px4.sequencer().state() == State::kInControl; }));
  std::uint64_t allocations = 0;
  for (int i = 0; i < 100; ++i) {
    rig.clock.advance(20ms);
    rig.world.step(rig.clock.now(), 0.02);
    rig.bridge.step(rig.clock.now());
    std::this_thread::sleep_for(1ms);
    test::AllocationCounter counter(test::AllocationCounter::Threads::kThisOne);
    const hal::FlightStatus s = rig.px4.update(rig.clock.now());
    hal::FlightSetpoint sp;
    sp.stamp = rig.clock.now();
    sp.position_m = Vec3(0, 0, 1.5);
    (void)rig.px4.send_setpoint(sp);
    hal::UavState st;
    (void)rig.px4.poll(st);
    allocations += counter.count();
    ASSERT_EQ(s.state, msg::UavFlight::kInControl);
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(rig.px4.counters().odometry, 50u);
}
