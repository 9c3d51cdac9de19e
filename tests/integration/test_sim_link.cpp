// The SITL sim link in one process: colag_world's bridge on one participant, a UGV's and the
// UAV's sim HAL on two others (the domain's own DDS traffic, over loopback). Every device
// carries its data across Cyclone: encoder frames reach the UGV, its commands move the body, the
// UAV's setpoints fly it, its state, LiDAR scans and camera frames arrive.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/hal/sim/sim_devices.hpp"
#include "colag/sim/bridge/world_bridge.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "dds_test_env.hpp"

using namespace colag;
using namespace std::chrono_literals;

namespace {

// Steps the world (50 Hz of simulated time per call) and the bridge until `done`, or 10 s.
bool run_until(sim::SimWorld& world, sim::WorldBridge& bridge, hal::scripted::ManualClock& clock,
               const std::function<void()>& robot_side, const std::function<bool()>& done) {
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (std::chrono::steady_clock::now() < deadline) {
    clock.advance(20ms);
    world.step(clock.now(), 0.02);
    bridge.step();
    std::this_thread::sleep_for(2ms);
    robot_side();
    if (done()) return true;
  }
  return false;
}

TEST(SimLink, EveryDeviceCrossesDdsBetweenTheWorldAndTheRobots) {
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  hal::scripted::ManualClock clock;
  sim::BoxWorld boxes;
  boxes.boxes.push_back({Vec2(3, 0), Vec2(0.4, 0.4), 0.6});
  sim::SimWorldConfig wc;
  wc.lidar.columns = 360;
  sim::SimWorld world(wc, boxes, clock);
  world.add_ugv({Vec2(0, 0), 0.0});
  world.add_uav(Vec3(0, 0, 1.5));

  hal::sim::SimLink world_link, ugv_link, uav_link;
  ASSERT_TRUE(world_link.init(domain, hal::sim::SimLink::Side::kWorld));
  ASSERT_TRUE(ugv_link.init(domain, hal::sim::SimLink::Side::kUgv, 0));
  ASSERT_TRUE(uav_link.init(domain, hal::sim::SimLink::Side::kUav));
  sim::WorldBridge bridge(world_link, world, true);
  hal::sim::SimCanBus bus(ugv_link, 0);
  hal::sim::SimUavDevices uav(uav_link);

  // The UGV: the real CAN drivers on the sim bus. Drive forward until the body has moved.
  hal::can::CanWheelOdometry odometry(bus, wc.ugv.base.colag, wc.ugv.geometry);
  hal::can::CanDrive drive(bus, wc.ugv.base.colag, wc.ugv.geometry);
  double odometry_m = 0.0;
  TimePoint last{};
  ASSERT_TRUE(run_until(
      world, bridge, clock,
      [&] {
        (void)drive.command({clock.now(), 0.3, 0.0});
        hal::WheelOdometrySample s;
        while (odometry.poll(s)) {
          if (last != TimePoint{}) odometry_m += s.v_mps * to_seconds(s.stamp - last);
          last = s.stamp;
        }
      },
      [&] { return world.ugv(0).pose().p.x() > 0.5; }))
      << "the UGV did not move: " << bus.stats().rx_frames << " frames in, "
      << bus.stats().tx_frames << " out";
  EXPECT_NEAR(odometry_m, world.ugv(0).pose().p.x(), 0.1);  // encoders saw the motion
  EXPECT_EQ(odometry.counters().bad_checksum + odometry.counters().wrong_dlc, 0u);

  // The UAV: climbing setpoints fly it up; its state, a scan and a camera frame arrive.
  hal::UavState state;
  hal::LidarScanView scan;
  std::array<hal::RelativePoseDetection, 4> seen{};
  bool got_state = false, got_scan = false;
  std::size_t detections = 0;
  std::size_t returns = 0;
  ASSERT_TRUE(run_until(
      world, bridge, clock,
      [&] {
        hal::FlightSetpoint sp;
        sp.stamp = clock.now();
        sp.position_m = Vec3(0, 0, 2.5);
        sp.velocity_mps = Vec3(0, 0, 0.5);  // the simulated body follows the velocity
        (void)uav.send_setpoint(sp);
        got_state = uav.poll(state) || got_state;
        if (uav.poll(scan)) {
          got_scan = true;
          returns = scan.points.size();
        }
        detections = std::max(detections, uav.poll(seen));
      },
      [&] { return got_state && got_scan && detections > 0 && state.pose.p.z() > 1.8; }))
      << "state " << got_state << " scan " << got_scan << " detections " << detections << " z "
      << state.pose.p.z();
  EXPECT_GT(returns, 100u);  // the ground and the box
  EXPECT_EQ(seen[0].ugv_id, 0);
  EXPECT_NEAR(state.pose.p.z(), world.uav().state().pose.p.z(), 0.2);
  EXPECT_EQ(uav.malformed(), 0u);
}

}  // namespace
