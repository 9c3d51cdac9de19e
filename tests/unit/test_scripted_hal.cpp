#include <gtest/gtest.h>

#include "colag/hal/scripted/scripted_devices.hpp"

using namespace colag;
using namespace colag::hal;
using namespace std::chrono_literals;

TEST(ScriptedHal, WheelOdometryDeliversInOrderAndTracksNewest) {
  scripted::ScriptedWheelOdometry odo;
  WheelOdometrySample s;
  EXPECT_FALSE(odo.poll(s));
  ASSERT_TRUE(odo.push({TimePoint{20ms}, 0.5, 0.1}));
  ASSERT_TRUE(odo.push({TimePoint{40ms}, 0.4, 0.0}));
  EXPECT_EQ(odo.last_sample_time(), TimePoint{40ms});
  ASSERT_TRUE(odo.poll(s));
  EXPECT_EQ(s.v_mps, 0.5);
  ASSERT_TRUE(odo.poll(s));
  EXPECT_EQ(s.v_mps, 0.4);
  EXPECT_FALSE(odo.poll(s));
}

TEST(ScriptedHal, DriveRecordsAndCanFail) {
  scripted::RecordingDrive drive;
  EXPECT_TRUE(drive.command({TimePoint{1s}, 0.3, -0.2}));
  EXPECT_EQ(drive.last().v_mps, 0.3);
  drive.fail_with({Errc::kIoError, "bus off"});
  EXPECT_EQ(drive.command({TimePoint{2s}, 0.1, 0.0}).code(), Errc::kIoError);
  EXPECT_EQ(drive.commands(), 1u);
  EXPECT_TRUE(drive.stop(TimePoint{3s}));  // stop works even when commands fail
  EXPECT_EQ(drive.last().v_mps, 0.0);
}

TEST(ScriptedHal, CanBusQueuesAndCounts) {
  scripted::ScriptedCanBus bus;
  CanFrame f;
  f.id = 0x101;
  f.dlc = 8;
  ASSERT_TRUE(bus.inject(f));
  CanFrame got;
  ASSERT_TRUE(bus.receive(got));
  EXPECT_EQ(got.id, 0x101u);
  EXPECT_FALSE(bus.receive(got));
  EXPECT_TRUE(bus.send(f, TimePoint{1s}));
  bus.fail_with({Errc::kTimeout, "tx full"});
  EXPECT_FALSE(bus.send(f, TimePoint{1s}));
  EXPECT_EQ(bus.stats().tx_frames, 1u);
  EXPECT_EQ(bus.stats().tx_failures, 1u);
  EXPECT_EQ(bus.stats().rx_frames, 1u);
}

TEST(ScriptedHal, RelativePoseSensorTruncatesToCallerBuffer) {
  scripted::ScriptedRelativePoseSensor rpe;
  scripted::ScriptedRelativePoseSensor::Frame frame;
  for (RobotId id = 0; id < 3; ++id) {
    RelativePoseDetection d;
    d.ugv_id = id;
    ASSERT_TRUE(frame.push_back(d));
  }
  ASSERT_TRUE(rpe.push_frame(frame));
  RelativePoseDetection out[2];
  EXPECT_EQ(rpe.poll(out), 2u);
  EXPECT_EQ(out[1].ugv_id, 1);
  EXPECT_EQ(rpe.poll(out), 0u);
}

TEST(ScriptedHal, LidarViewsTheScanOnce) {
  static scripted::ScriptedLidar lidar;  // large: keep it off the stack
  const LidarPoint pts[] = {{1, 0, 0}, {0, 2, 0}};
  ASSERT_TRUE(lidar.set_scan(TimePoint{100ms}, 8.0F, pts));
  LidarScanView view;
  ASSERT_TRUE(lidar.poll(view));
  EXPECT_EQ(view.points.size(), 2u);
  EXPECT_EQ(view.points[1].y_m, 2.0F);
  EXPECT_FALSE(lidar.poll(view));
}

TEST(ScriptedHal, ClockAndFlightController) {
  scripted::ManualClock clock;
  clock.advance(150ms);
  EXPECT_EQ(clock.now(), TimePoint{150ms});
  scripted::RecordingFlightController fc;
  FlightSetpoint sp;
  sp.position_m = Vec3(1, 2, 1);
  EXPECT_TRUE(fc.send_setpoint(sp));
  EXPECT_EQ(fc.last().position_m.y(), 2.0);
  EXPECT_EQ(fc.count(), 1u);
  scripted::ScriptedOdometrySource odom;
  UavState st;
  st.stamp = TimePoint{1s};
  ASSERT_TRUE(odom.push(st));
  UavState got;
  ASSERT_TRUE(odom.poll(got));
  EXPECT_EQ(got.stamp, TimePoint{1s});
}
