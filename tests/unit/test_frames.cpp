// The one place where ENU/FLU meet NED/FRD: known directions, headings and round trips.
#include "colag/common/frames.hpp"

#include <gtest/gtest.h>

#include "colag/common/random.hpp"

using namespace colag;

namespace {

void expect_near(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR((a - b).norm(), 0.0, 1e-12) << a.transpose() << " vs " << b.transpose();
}

}  // namespace

TEST(Frames, WorldPointsSwapNorthAndEastAndFlipUp) {
  expect_near(frames::enu_to_ned(Vec3(1, 0, 0)), Vec3(0, 1, 0));   // east
  expect_near(frames::enu_to_ned(Vec3(0, 1, 0)), Vec3(1, 0, 0));   // north
  expect_near(frames::enu_to_ned(Vec3(0, 0, 2)), Vec3(0, 0, -2));  // 2 m up is z = -2
  expect_near(frames::ned_to_enu(frames::enu_to_ned(Vec3(3, -4, 5))), Vec3(3, -4, 5));
}

TEST(Frames, BodyVectorsKeepForwardAndFlipLeftAndUp) {
  expect_near(frames::flu_to_frd(Vec3(1, 2, 3)), Vec3(1, -2, -3));
  expect_near(frames::frd_to_flu(frames::flu_to_frd(Vec3(1, 2, 3))), Vec3(1, 2, 3));
}

TEST(Frames, AnAttitudeMapsTheSameBodyAxesToTheSameWorldDirections) {
  Rng rng(5);
  for (int i = 0; i < 100; ++i) {
    const Quat q_enu_flu =
        Quat(rng.gaussian(0, 1), rng.gaussian(0, 1), rng.gaussian(0, 1), rng.gaussian(0, 1))
            .normalized();
    const Quat q_ned_frd = frames::enu_flu_to_ned_frd(q_enu_flu);
    const Vec3 v_flu(rng.gaussian(0, 1), rng.gaussian(0, 1), rng.gaussian(0, 1));
    // The same physical vector, expressed in each convention, lands on the same direction.
    expect_near(q_ned_frd * frames::flu_to_frd(v_flu), frames::enu_to_ned(q_enu_flu * v_flu));
    const Quat back = frames::ned_frd_to_enu_flu(q_ned_frd);
    EXPECT_NEAR(std::abs(back.dot(q_enu_flu)), 1.0, 1e-12);
  }
}

TEST(Frames, HeadingsFacingEastAndNorth) {
  // Facing east: ENU yaw 0, NED yaw +90 deg; facing north: ENU 90 deg, NED 0.
  EXPECT_NEAR(frames::enu_yaw_to_ned(0.0), M_PI / 2, 1e-12);
  EXPECT_NEAR(frames::enu_yaw_to_ned(M_PI / 2), 0.0, 1e-12);
  EXPECT_NEAR(frames::ned_yaw_to_enu(frames::enu_yaw_to_ned(-2.5)), -2.5, 1e-12);
  // The attitude and the heading conversions agree.
  const Quat q_ned_frd = frames::enu_flu_to_ned_frd(quat_from_yaw(0.7));
  const Vec3 fwd = q_ned_frd * Vec3::UnitX();
  EXPECT_NEAR(std::atan2(fwd.y(), fwd.x()), frames::enu_yaw_to_ned(0.7), 1e-12);
}
