#include <gtest/gtest.h>

#include "colag/uav/camera_altitude.hpp"
#include "colag/uav/no_return_beams.hpp"

using namespace colag;
using namespace colag::uav;

TEST(CameraAltitude, FliesWhereTheConeMeetsTheRangeWithinItsLimits) {
  // 75 deg, 5 m, tags 0.3 m up: 0.3 + 5 cos 75 = 1.594 m.
  EXPECT_NEAR(camera_altitude({5.0, 75.0, 0.3}, 1.0, 3.0),
              0.3 + 5.0 * std::cos(75.0 * M_PI / 180.0), 1e-12);
  // There the disc it sees on the tags' plane is widest: from lower the cone limits it, from
  // higher the range.
  const auto disc = [](double h) {
    const double d = h - 0.3;
    return std::min(d * std::tan(75.0 * M_PI / 180.0), std::sqrt(std::max(0.0, 25.0 - d * d)));
  };
  const double best = camera_altitude({5.0, 75.0, 0.3}, 0.5, 3.0);
  EXPECT_GT(disc(best), disc(best - 0.1));
  EXPECT_GT(disc(best), disc(best + 0.1));
  EXPECT_NEAR(disc(best), 5.0 * std::sin(75.0 * M_PI / 180.0), 1e-9);
  // A camera that sees in every direction, or one not described: as configured.
  EXPECT_EQ(camera_altitude({5.0, 180.0, 0.3}, 1.0, 3.0), 1.0);
  EXPECT_EQ(camera_altitude({}, 1.0, 3.0), 1.0);
  // Never below the lowest nor above the highest.
  EXPECT_EQ(camera_altitude({20.0, 30.0, 0.3}, 1.0, 3.0), 3.0);
  EXPECT_EQ(camera_altitude({1.0, 85.0, 0.3}, 1.0, 3.0), 1.0);
}

TEST(LidarAltitudeLimit, LeavesTheBlindDiscOnTheBodyBandNoWiderThanAsked) {
  // -25.2 deg, the band from 0.1 m, 3.2 m: 0.1 + 3.2 tan 25.2 deg = 1.606 m.
  const double h = lidar_altitude_limit(-25.2, 0.1, 3.2, 1.0, 3.0);
  EXPECT_NEAR(h, 0.1 + 3.2 * std::tan(25.2 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR((h - 0.1) / std::tan(25.2 * M_PI / 180.0), 3.2, 1e-12);
  // A steeper lowest beam flies higher, within the hard ceiling.
  EXPECT_GT(lidar_altitude_limit(-40.0, 0.1, 3.2, 1.0, 3.0), 2.7);
  EXPECT_EQ(lidar_altitude_limit(-60.0, 0.1, 3.2, 1.0, 3.0), 3.0);
  EXPECT_EQ(lidar_altitude_limit(-90.0, 0.1, 3.2, 1.0, 3.0), 3.0);
  // One that cannot look down, or is not described: no higher than the configured altitude.
  EXPECT_EQ(lidar_altitude_limit(0.0, 0.1, 3.2, 1.0, 3.0), 1.0);
  EXPECT_EQ(lidar_altitude_limit(15.0, 0.1, 3.2, 1.0, 3.0), 1.0);
  EXPECT_EQ(lidar_altitude_limit(std::nan(""), 0.1, 3.2, 1.0, 3.0), 1.0);
  EXPECT_EQ(lidar_altitude_limit(-25.2, 0.1, 0.0, 1.0, 3.0), 1.0);
}

TEST(CameraReach, WhereTheTagLeavesTheConeOrTheRange) {
  // 75 deg, 5 m, tags 0.3 m up, from 1.6 m: the cone 1.3 tan 75 = 4.85, the range 4.83.
  EXPECT_NEAR(camera_reach({5.0, 75.0, 0.3}, 1.6), std::sqrt(25.0 - 1.3 * 1.3), 1e-12);
  // From 0.7 m the cone ends first: 0.4 tan 75.
  EXPECT_NEAR(camera_reach({5.0, 75.0, 0.3}, 0.7), 0.4 * std::tan(75.0 * M_PI / 180.0), 1e-12);
  // camera_altitude() flies where it is widest.
  const CameraView v{5.0, 75.0, 0.3};
  const double best = camera_reach(v, camera_altitude(v, 0.5, 3.0));
  EXPECT_GT(best, camera_reach(v, camera_altitude(v, 0.5, 3.0) + 0.1));
  EXPECT_GT(best, camera_reach(v, camera_altitude(v, 0.5, 3.0) - 0.1));
  // Beyond its range straight down, nothing; not described or not above the tag: no limit.
  EXPECT_EQ(camera_reach(v, 5.4), 0.0);
  EXPECT_TRUE(std::isinf(camera_reach({}, 1.6)));
  EXPECT_TRUE(std::isinf(camera_reach(v, 0.3)));
}

TEST(LidarBlindRadius, IsWhatTheAltitudeLimitInverts) {
  const double h = lidar_altitude_limit(-25.2, 0.1, 3.2, 1.0, 3.0);
  EXPECT_NEAR(lidar_blind_radius(-25.2, h, 0.1), 3.2, 1e-12);
  EXPECT_EQ(lidar_blind_radius(-90.0, 1.6, 0.1), 0.0);
  EXPECT_TRUE(std::isnan(lidar_blind_radius(0.0, 1.6, 0.1)));
  EXPECT_TRUE(std::isnan(lidar_blind_radius(std::nan(""), 1.6, 0.1)));
  EXPECT_TRUE(std::isnan(lidar_blind_radius(-25.2, 0.05, 0.1)));  // below the band
}

TEST(LidarAltitudeLimit, TheBlindConeFollowsHowTheLidarIsMounted) {
  const LidarBeamPattern vlp{32, -25.2, 1.2, 1200};
  const auto about_y = [](double deg) {
    return Quat(Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitY()));
  };
  EXPECT_NEAR(blind_cone_elevation_deg(vlp, Quat::Identity()), -25.2, 1e-9);
  // Tilted 10 deg: on one side its lowest beam looks 10 deg less down.
  EXPECT_NEAR(blind_cone_elevation_deg(vlp, about_y(10.0)), -15.2, 0.1);
  // Upside down, its highest beam (+12 deg) is the lowest.
  EXPECT_NEAR(blind_cone_elevation_deg(vlp, about_y(180.0)), -(-25.2 + 31 * 1.2), 1e-6);
  EXPECT_TRUE(std::isnan(blind_cone_elevation_deg({}, Quat::Identity())));
}
