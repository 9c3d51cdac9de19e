// The UAV's relay of the UGVs near each UGV (uav/nearby_relay.hpp).
#include <gtest/gtest.h>

#include <array>

#include "colag/uav/nearby_relay.hpp"

using namespace colag;
using namespace std::chrono_literals;

namespace {

struct Heard {
  bool known = false;
  TimePoint heard{};
  msg::UgvStatus status;
};

Heard at(double x, double y, TimePoint heard) {
  Heard h;
  h.known = true;
  h.heard = heard;
  h.status.position_m[0] = x;
  h.status.position_m[1] = y;
  h.status.covariance[0] = 0.01;
  h.status.covariance[1] = 0.002;
  h.status.covariance[4] = 0.03;
  h.status.velocity_mps = 0.4;
  return h;
}

}  // namespace

TEST(NearbyRelay, ListsTheUgvsWithinTheRadiusNearestFirstASilentOneAsFarAsItCanHaveDriven) {
  const TimePoint now{100s};
  std::array<Heard, limits::kMaxUgvs> ugvs{};
  ugvs[0] = at(0, 0, now);
  ugvs[1] = at(11, 0, now);            // within 12 m
  ugvs[2] = at(0, 5, now);             // nearer
  ugvs[3] = at(20, 0, now);            // too far
  ugvs[4] = at(20, 0, now - 20s);      // as far, but silent for 20 s: may be 14 m nearer by now
  ugvs[5].status.position_m[0] = 1.0;  // never heard
  msg::NearbyUgvs out;
  uav::fill_nearby(0, ugvs, now, uav::NearbyRelayConfig{}, 12.0, out);
  EXPECT_EQ(out.ugv_id, 0);
  EXPECT_DOUBLE_EQ(out.radius_m, 12.0);
  ASSERT_EQ(out.ugvs.size(), 3u);
  // By how near each may be now: the silent one may be 6 m away.
  EXPECT_EQ(out.ugvs[0].ugv_id, 2);
  EXPECT_EQ(out.ugvs[1].ugv_id, 4);
  EXPECT_EQ(out.ugvs[2].ugv_id, 1);
  EXPECT_FLOAT_EQ(out.ugvs[1].silent_s, 20.0F);
  EXPECT_FLOAT_EQ(out.ugvs[0].silent_s, 0.0F);
  // What the UGV plans with: position, the position's covariance, velocity (single precision
  // on the wire).
  EXPECT_FLOAT_EQ(out.ugvs[0].position_m[1], 5.0F);
  EXPECT_FLOAT_EQ(out.ugvs[0].covariance_xy[0], 0.01F);
  EXPECT_FLOAT_EQ(out.ugvs[0].covariance_xy[1], 0.002F);
  EXPECT_FLOAT_EQ(out.ugvs[0].covariance_xy[2], 0.03F);
  EXPECT_FLOAT_EQ(out.ugvs[0].velocity_mps, 0.4F);

  // A crowd: only the nearest kMaxNearbyUgvs, and never the UGV itself.
  for (std::size_t i = 1; i < ugvs.size(); ++i)
    ugvs[i] = at(0.5 * static_cast<double>(i), 0, now);
  uav::fill_nearby(3, ugvs, now, uav::NearbyRelayConfig{}, 12.0, out);
  ASSERT_EQ(out.ugvs.size(), limits::kMaxNearbyUgvs);
  // Complete only up to the first left out (UGV 13, 5 m from UGV 3; the twelve listed are
  // within 4.5 m), and it says so.
  EXPECT_DOUBLE_EQ(out.radius_m, 5.0);
  double last = 0.0;
  for (const msg::NearbyUgv& u : out.ugvs) {
    EXPECT_NE(u.ugv_id, 3);
    const double d = std::abs(u.position_m[0] - 1.5);
    EXPECT_GE(d, last);
    last = d;
  }
}

TEST(NearbyRelay, ListsTheFarOnesOnlyEveryFullEveryThPass) {
  const TimePoint now{100s};
  std::array<Heard, limits::kMaxUgvs> ugvs{};
  ugvs[0] = at(0, 0, now);
  ugvs[1] = at(3, 0, now);              // near
  ugvs[2] = at(0, 9, now);              // far: full lists only
  ugvs[3] = at(0, 30, now);             // beyond every list
  const uav::NearbyRelayConfig config;  // full every second pass
  std::array<int, 4> listed{};
  std::array<double, 4> radius{};
  for (std::uint64_t pass = 0; pass < 4; ++pass) {
    msg::NearbyUgvs out;
    const int sent =
        uav::relay_nearby(ugvs, now, 1s, config, pass, out, [&](const msg::NearbyUgvs& m) {
          if (m.ugv_id == 0) {
            listed[pass] = static_cast<int>(m.ugvs.size());
            radius[pass] = m.radius_m;
          }
          return true;
        });
    EXPECT_EQ(sent, 4);
  }
  EXPECT_EQ(listed, (std::array<int, 4>{2, 1, 2, 1}));
  EXPECT_EQ(radius, (std::array<double, 4>{12.0, 6.0, 12.0, 6.0}));

  uav::NearbyRelayConfig every;
  every.full_every = 1;
  EXPECT_DOUBLE_EQ(uav::nearby_radius(every, 1), 12.0);
  every.full_every = 0;  // as 1
  EXPECT_DOUBLE_EQ(uav::nearby_radius(every, 3), 12.0);
}
