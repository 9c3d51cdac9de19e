// The field world's UAV odometry (a LiDAR-inertial odometry's frame, late), and what the UAV
// firmware does with a late odometry: predict it to the moment it needs, ramp its setpoints.
#include <gtest/gtest.h>

#include <deque>

#include "colag/common/map_store.hpp"
#include "colag/sim/world/uav_body.hpp"
#include "colag/uav/flight_planner.hpp"
#include "colag/uav/state_prediction.hpp"

using namespace colag;
using namespace colag::sim;
using namespace std::chrono_literals;

TEST(OdometryFrame, IsASimilarityAboutWhereItStartedPlusWhatItWalked) {
  UavOdometryErrors e;
  e.scale_error = 0.005;
  e.yaw_error_rad = 0.005;
  const Vec3 origin(-15.0, -15.0, 1.0);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    OdometryFrame f(e, origin, seed);
    EXPECT_LE(std::abs(f.yaw_error_rad()), 0.005);
    EXPECT_LT((f.to_odometry(origin) - origin).norm(), 1e-12);  // no walk: the origin is fixed
    // 30 m away it is off by at most 0.5 % plus the heading's 0.5 % (0.3 deg): 0.21 m.
    const Vec3 far = origin + Vec3(30.0, 0.0, 0.0);
    EXPECT_LE((f.to_odometry(far) - far).norm(), 30.0 * std::hypot(0.005, 0.005) + 1e-9);
    const Vec3 v(1.0, -2.0, 0.5);
    EXPECT_LT((f.vector_to_world(f.vector_to_odometry(v)) - v).norm(), 1e-12);
  }
  // The walk moves the whole frame, slowly: 0.02 m per sqrt(minute) is ~0.02 m after a minute.
  e = {};
  e.walk_m_per_sqrt_s = 0.02 / std::sqrt(60.0);
  double sq = 0.0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    OdometryFrame f(e, origin, seed);
    for (int k = 0; k < 3000; ++k)
      f.step(0.02);
    sq += (f.to_odometry(origin) - origin).head<2>().squaredNorm() / 200.0;
  }
  EXPECT_NEAR(std::sqrt(sq), 0.02 * std::sqrt(2.0), 0.006);
}

TEST(UavBody, DeliversItsOdometryLateStampedWhenMeasured) {
  UavBodyConfig c;
  c.odometry.latency = 60ms;
  UavBody uav(c, Vec3(0, 0, 1));
  hal::FlightSetpoint sp;
  sp.velocity_mps = Vec3(1.0, 0.0, 0.0);
  ASSERT_TRUE(uav.send_setpoint(sp));
  TimePoint t{};
  int delivered = 0;
  for (int k = 0; k < 100; ++k) {
    t += 20ms;
    uav.step(t, 0.02);
    hal::UavState s;
    while (uav.poll(s)) {
      ++delivered;
      EXPECT_EQ(t - s.stamp, 60ms);
    }
  }
  EXPECT_EQ(delivered, 97);  // the last three are still on their way
}

TEST(UavBody, IdealOdometryIsTheTruthAtOnce) {
  UavBody uav({}, Vec3(1, 2, 1));
  uav.step(TimePoint{} + 20ms, 0.02);
  hal::UavState s;
  ASSERT_TRUE(uav.poll(s));
  EXPECT_EQ(s.stamp, TimePoint{} + 20ms);
  EXPECT_EQ(s.pose.p, uav.state().pose.p);
}

TEST(StatePrediction, MovesTheSampleOnByItsVelocityUpToTheLimit) {
  hal::UavState s;
  s.stamp = TimePoint{} + 1s;
  s.pose.p = Vec3(1, 0, 1);
  s.velocity_mps = Vec3(3, 0, 0);
  EXPECT_NEAR(uav::predict_state(s, s.stamp + 20ms, 200ms).pose.p.x(), 1.06, 1e-12);
  EXPECT_NEAR(uav::predict_state(s, s.stamp + 1s, 200ms).pose.p.x(), 1.6, 1e-12);
  EXPECT_EQ(uav::predict_state(s, s.stamp - 1s, 200ms).pose.p, s.pose.p);  // never backwards
}

// A UAV whose odometry is one control period late still accelerates at its limit: the setpoints
// ramp from the last setpoint, not from the velocity measured a period ago (which halved it).
TEST(FlightPlanner, AcceleratesAtItsLimitOnAnOdometryOnePeriodLate) {
  for (const Duration latency : {0ms, 20ms, 60ms}) {
    UavBodyConfig bc;
    bc.odometry.latency = latency;
    UavBody uav(bc, Vec3(0, 0, 1));
    uav::FlightPlanner planner({});
    MapStore empty;
    TimePoint t{};
    hal::UavState s;
    hal::UavState latest = uav.state();
    planner.set_target(Vec2(40.0, 0.0), t, Vec2::Zero(), empty);
    double reached_cruise_s = -1.0;
    for (int k = 0; k < 500 && reached_cruise_s < 0.0; ++k) {
      t += 20ms;
      uav.step(t, 0.02);
      while (uav.poll(s))
        latest = s;
      ASSERT_TRUE(
          uav.send_setpoint(planner.step(uav::predict_state(latest, t, 200ms), t, 0.02, empty)));
      if (uav.state().velocity_mps.x() >= 2.9) reached_cruise_s = to_seconds(t - TimePoint{});
    }
    // 3 m/s at 1 m/s^2: 3 s (the first setpoint is a period late); 6 s with the stale ramp.
    EXPECT_GT(reached_cruise_s, 0.0) << to_seconds(latency);
    EXPECT_LT(reached_cruise_s, 3.3) << to_seconds(latency);
  }
}
