#include <gtest/gtest.h>

#include "colag/uav/camera_altitude.hpp"

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
