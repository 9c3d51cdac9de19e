#include <gtest/gtest.h>

#include "colag/ugv/rpe_measurement.hpp"

using namespace colag;
using namespace colag::ugv;
using namespace std::chrono_literals;

namespace {
msg::UavOdometry odom(TimePoint t, Vec3 p, double yaw) {
  msg::UavOdometry m;
  m.stamp = t;
  m.position_m[0] = p.x();
  m.position_m[1] = p.y();
  m.position_m[2] = p.z();
  const Quat q = quat_from_yaw(yaw);
  m.orientation_wxyz[0] = q.w();
  m.orientation_wxyz[1] = q.x();
  m.orientation_wxyz[2] = q.y();
  m.orientation_wxyz[3] = q.z();
  return m;
}
}  // namespace

TEST(RpeMeasurement, ComposesUavPoseAndRelativePoseAndRotatesTheCovariance) {
  const Pose3 uav{Vec3(2.0, 1.0, 1.0), quat_from_yaw(M_PI / 2)};
  msg::RelativePose rpe;
  rpe.stamp = TimePoint{3s};
  rpe.position_m[0] = 1.0;  // 1 m ahead of the UAV, 1 m below
  rpe.position_m[2] = -1.0;
  const Quat q = quat_from_yaw(0.3);
  rpe.orientation_wxyz[0] = q.w();
  rpe.orientation_wxyz[3] = q.z();
  // sigma_x 0.3 (UAV forward), sigma_y 0.1, sigma_z 0.1, sigma_yaw 0.05
  rpe.covariance[0] = 0.09;
  rpe.covariance[5] = 0.01;
  rpe.covariance[10] = 0.01;
  rpe.covariance[15] = 0.0025;
  const auto z = world_measurement(rpe, uav);
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->pose.p.x(), 2.0, 1e-12);  // UAV faces +y: its forward is world +y
  EXPECT_NEAR(z->pose.p.y(), 2.0, 1e-12);
  EXPECT_NEAR(z->pose.yaw_rad, M_PI / 2 + 0.3, 1e-12);
  EXPECT_NEAR(z->covariance(0, 0), 0.01, 1e-12);  // world x is the UAV's lateral axis
  EXPECT_NEAR(z->covariance(1, 1), 0.09, 1e-12);
  EXPECT_NEAR(z->covariance(2, 2), 0.0025, 1e-12);
  EXPECT_EQ(z->stamp, TimePoint{3s});
}

TEST(RpeMeasurement, RejectsMalformedRelativePoses) {
  const Pose3 uav;
  msg::RelativePose rpe;
  rpe.covariance[0] = rpe.covariance[5] = rpe.covariance[10] = rpe.covariance[15] = 0.01;
  EXPECT_TRUE(world_measurement(rpe, uav));
  msg::RelativePose bad = rpe;
  bad.position_m[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(world_measurement(bad, uav));
  bad = rpe;
  bad.orientation_wxyz[0] = 2.0;  // not a unit quaternion
  EXPECT_FALSE(world_measurement(bad, uav));
  bad = rpe;
  bad.covariance[15] = 0.0;
  EXPECT_FALSE(world_measurement(bad, uav));
  bad = rpe;
  bad.covariance[3] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(world_measurement(bad, uav));
}

TEST(UavOdometryHistory, InterpolatesAndRefusesDistantStamps) {
  UavOdometryHistory h;
  ASSERT_TRUE(h.push(odom(TimePoint{1000ms}, Vec3(0, 0, 1), 0.0)));
  ASSERT_TRUE(h.push(odom(TimePoint{1020ms}, Vec3(0.2, 0, 1), 0.2)));
  EXPECT_FALSE(h.push(odom(TimePoint{1020ms}, Vec3(9, 9, 9), 0.0)));  // stamp not increasing
  msg::UavOdometry nan = odom(TimePoint{1040ms}, Vec3(0, 0, 1), 0.0);
  nan.position_m[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(h.push(nan));
  Pose3 p;
  ASSERT_TRUE(h.pose_at(TimePoint{1005ms}, 100ms, p));
  EXPECT_NEAR(p.p.x(), 0.05, 1e-12);
  EXPECT_NEAR(yaw_of(p.q), 0.05, 1e-9);
  ASSERT_TRUE(h.pose_at(TimePoint{1100ms}, 100ms, p));  // 80 ms after the newest: nearest
  EXPECT_NEAR(p.p.x(), 0.2, 1e-12);
  EXPECT_FALSE(h.pose_at(TimePoint{1130ms}, 100ms, p));  // 110 ms: too far
  EXPECT_FALSE(h.pose_at(TimePoint{800ms}, 100ms, p));
}

// The UAV publishes its odometry at 20 Hz and a detection can be newer than the newest sample a
// UGV has: that sample moved on by its velocity, not the sample itself (at 3 m/s, 50 ms is
// 15 cm of error in every relative pose placed that way).
TEST(UavOdometryHistory, CarriesTheNewestSampleOnByItsVelocity) {
  UavOdometryHistory h;
  msg::UavOdometry m = odom(TimePoint{1000ms}, Vec3(1, 2, 1.5), 0.5);
  m.velocity_mps[0] = 3.0;
  m.velocity_mps[1] = -1.0;
  m.yaw_rate_radps = 0.4;
  ASSERT_TRUE(h.push(m));
  Pose3 p;
  ASSERT_TRUE(h.pose_at(TimePoint{1050ms}, 100ms, p));
  EXPECT_NEAR(p.p.x(), 1.15, 1e-12);
  EXPECT_NEAR(p.p.y(), 1.95, 1e-12);
  EXPECT_NEAR(p.p.z(), 1.5, 1e-12);
  EXPECT_NEAR(yaw_of(p.q), 0.52, 1e-9);
  EXPECT_FALSE(h.pose_at(TimePoint{1101ms}, 100ms, p));  // beyond the tolerance all the same
  ASSERT_TRUE(h.pose_at(TimePoint{950ms}, 100ms, p));    // before the oldest: the oldest
  EXPECT_NEAR(p.p.x(), 1.0, 1e-12);
  // A velocity that is not finite moves nothing (the pose still places detections).
  msg::UavOdometry bad = odom(TimePoint{1100ms}, Vec3(2, 2, 1.5), 0.0);
  bad.velocity_mps[0] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(h.push(bad));
  ASSERT_TRUE(h.pose_at(TimePoint{1150ms}, 100ms, p));
  EXPECT_NEAR(p.p.x(), 2.0, 1e-12);
  EXPECT_TRUE(p.p.allFinite());
}
