#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "colag/uav/edge_orbit.hpp"

using namespace colag::uav;

TEST(EdgeOrbit, JustOutsideTheBlindDiscWithinTheCamerasReach) {
  const double down = 25.2 * M_PI / 180.0;
  const CameraView wide{5.0, 75.0, 0.3};  // reaches a tag ~4.8 m out from 1.6 m
  // From 1.6 m over a body band from 0.1 m, a -25.2 deg beam leaves a 3.2 m disc: 3.8 m.
  EXPECT_NEAR(edge_orbit_radius(-25.2, 1.6, 0.1, wide, 0.6, 2.0), 1.5 / std::tan(down) + 0.6,
              1e-12);
  // A camera that does not reach that far (3 m: sqrt(3^2 - 1.3^2) - 0.3 = 2.4 m; a 60 deg cone,
  // 1.3 tan 60 - 0.3 = 1.95 m): no circle sees both, the usual orbit is left.
  EXPECT_TRUE(std::isnan(edge_orbit_radius(-25.2, 1.6, 0.1, {3.0, 75.0, 0.3}, 0.6, 2.0)));
  EXPECT_TRUE(std::isnan(edge_orbit_radius(-25.2, 1.6, 0.1, {5.0, 60.0, 0.3}, 0.6, 2.0)));
  // A camera not described does not limit it.
  EXPECT_NEAR(edge_orbit_radius(-25.2, 1.6, 0.1, {}, 0.6, 2.0), 1.5 / std::tan(down) + 0.6, 1e-12);
  // A LiDAR that looks straight down has no blind disc: round the UGV at the usual radius.
  EXPECT_EQ(edge_orbit_radius(-90.0, 1.6, 0.1, wide, 0.6, 2.0), 2.0);
  // One not described (NaN), one that does not look down, or one flying below the band: none.
  EXPECT_TRUE(std::isnan(
      edge_orbit_radius(std::numeric_limits<double>::quiet_NaN(), 1.6, 0.1, wide, 0.6, 2.0)));
  EXPECT_TRUE(std::isnan(edge_orbit_radius(5.0, 1.6, 0.1, wide, 0.6, 2.0)));
  EXPECT_TRUE(std::isnan(edge_orbit_radius(-25.2, 0.05, 0.1, wide, 0.6, 2.0)));
}
