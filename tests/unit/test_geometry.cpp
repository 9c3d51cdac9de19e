#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "colag/common/fast_atan2.hpp"
#include "colag/common/geometry.hpp"

using namespace colag;

TEST(Geometry, WrapAngleIntoHalfOpenRange) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.3), 0.3);
  EXPECT_DOUBLE_EQ(wrap_angle(M_PI), -M_PI);
  EXPECT_DOUBLE_EQ(wrap_angle(-M_PI), -M_PI);
  EXPECT_NEAR(wrap_angle(2 * M_PI + 0.1), 0.1, 1e-12);
  EXPECT_NEAR(wrap_angle(-2 * M_PI - 0.1), -0.1, 1e-12);
  EXPECT_NEAR(wrap_angle(3 * M_PI - 0.2), M_PI - 0.2, 1e-12);
  EXPECT_NEAR(wrap_angle(1000.0), std::remainder(1000.0, 2 * M_PI), 1e-9);
  for (double a = -50.0; a < 50.0; a += 0.37) {
    const double w = wrap_angle(a);
    EXPECT_GE(w, -M_PI);
    EXPECT_LT(w, M_PI);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-9);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-9);
  }
}

TEST(Geometry, Pose2ComposeAndInverse) {
  const Pose2 a{{1.0, 2.0}, M_PI / 2};
  const Pose2 b{{3.0, 0.0}, 0.5};
  const Pose2 ab = a.compose(b);
  EXPECT_NEAR(ab.p.x(), 1.0, 1e-12);  // b's x axis points along a's y
  EXPECT_NEAR(ab.p.y(), 5.0, 1e-12);
  EXPECT_NEAR(ab.yaw_rad, M_PI / 2 + 0.5, 1e-12);
  const Pose2 id = a.compose(a.inverse());
  EXPECT_NEAR(id.p.norm(), 0.0, 1e-12);
  EXPECT_NEAR(id.yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(wrap_angle(Pose2{{0, 0}, 3.0}.compose({{0, 0}, 0.5}).yaw_rad), 3.5 - 2 * M_PI, 1e-12);
}

TEST(Geometry, Pose3ComposeInverseAndYaw) {
  const Pose3 uav{{2.0, -1.0, 1.0}, quat_from_yaw(0.7)};
  const Pose3 rel{{0.5, 0.2, -1.0}, quat_from_yaw(-0.2)};
  const Pose3 ugv = uav.compose(rel);
  EXPECT_NEAR(yaw_of(ugv.q), 0.5, 1e-12);
  EXPECT_NEAR(ugv.p.z(), 0.0, 1e-12);
  const Pose3 back = uav.inverse().compose(ugv);
  EXPECT_NEAR((back.p - rel.p).norm(), 0.0, 1e-12);
  EXPECT_NEAR(back.q.angularDistance(rel.q), 0.0, 1e-9);
  // Heading is still read correctly under a 10 degree tilt.
  const Quat tilted = quat_from_yaw(1.2) * Quat(Eigen::AngleAxisd(0.17, Vec3::UnitY()));
  EXPECT_NEAR(yaw_of(tilted), 1.2, 1e-12);
  const Pose2 flat = to_pose2(ugv);
  EXPECT_NEAR(flat.yaw_rad, 0.5, 1e-12);
}

TEST(FastAtan2, WithinTwoHundredthsOfAMicroradianOfStdAtan2AllRound) {
  double worst = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const double t = -M_PI + 2.0 * M_PI * k / 100000.0;
    for (const double r : {1e-3, 1.0, 200.0}) {
      const double x = r * std::cos(t), y = r * std::sin(t);
      worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
    }
  }
  EXPECT_LT(worst, 2e-8);
  // The axes and the special values as std::atan2 has them (a LiDAR column is binned from it).
  EXPECT_DOUBLE_EQ(fast_atan2(0.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(fast_atan2(1.0, 0.0), M_PI_2);
  EXPECT_DOUBLE_EQ(fast_atan2(-1.0, 0.0), -M_PI_2);
  EXPECT_DOUBLE_EQ(fast_atan2(0.0, -1.0), M_PI);
  EXPECT_NEAR(fast_atan2(1.0, 1.0), M_PI_4, 2e-8);
  EXPECT_EQ(fast_atan2(0.0, 0.0), 0.0);
  EXPECT_TRUE(std::isnan(fast_atan2(std::nan(""), 1.0)));
  EXPECT_DOUBLE_EQ(fast_atan2(INFINITY, 1.0), M_PI_2);
}
