// Message struct <-> IDL sample mapping: every field of every type survives the round trip,
// and what the struct cannot hold is rejected.
#include <gtest/gtest.h>

#include "colag/common/random.hpp"
#include "colag/platform/dds/convert.hpp"

using namespace colag;
using namespace colag::platform::dds;

namespace {

class Filler {
 public:
  explicit Filler(std::uint64_t seed) : rng_(seed) {}
  double real() { return rng_.uniform(-100.0, 100.0); }
  template <std::size_t N>
  void fill(double (&a)[N]) {
    for (double& x : a)
      x = real();
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(rng_.below(65536)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(rng_.next_u64()); }
  TimePoint stamp() { return TimePoint{Duration{static_cast<std::int64_t>(rng_.next_u64() >> 1)}}; }
  std::uint64_t below(std::uint64_t n) { return rng_.below(n); }

 private:
  Rng rng_;
};

template <class Msg>
Msg round_trip(const Msg& in) {
  IdlSample<Msg> idl;
  to_idl(in, idl);
  Msg out;
  EXPECT_TRUE(from_idl(idl.sample, out));
  return out;
}

}  // namespace

TEST(DdsConvert, RoundTripEveryTypeOnRandomSamples) {
  Filler f(2024);
  for (int trial = 0; trial < 200; ++trial) {
    msg::UavOdometry od;
    od.stamp = f.stamp();
    od.uav_id = f.u16();
    f.fill(od.position_m);
    f.fill(od.orientation_wxyz);
    f.fill(od.velocity_mps);
    od.yaw_rate_radps = f.real();
    EXPECT_TRUE(round_trip(od) == od);

    msg::RelativePose rp;
    rp.stamp = f.stamp();
    rp.uav_id = f.u16();
    rp.ugv_id = f.u16();
    f.fill(rp.position_m);
    f.fill(rp.orientation_wxyz);
    f.fill(rp.covariance);
    EXPECT_TRUE(round_trip(rp) == rp);

    msg::MapPatch mp;
    mp.stamp = f.stamp();
    mp.uav_id = f.u16();
    mp.ugv_id = f.u16();
    mp.seq = f.u32();
    mp.resolution_m = f.real();
    mp.origin_x_m = f.real();
    mp.origin_y_m = f.real();
    mp.width_cells = f.u16();
    mp.height_cells = f.u16();
    mp.encoding = static_cast<msg::MapPatchEncoding>(f.below(3));
    mp.data_bytes = static_cast<std::uint16_t>(f.below(limits::kMaxPatchBytes + 1));
    for (std::size_t i = 0; i < mp.data_bytes; ++i)
      mp.data[i] = static_cast<std::uint8_t>(f.u16());
    EXPECT_TRUE(round_trip(mp) == mp);

    msg::CollisionInfo ci;
    ci.stamp = f.stamp();
    ci.ugv_id = f.u16();
    ci.seq = f.u32();
    ci.cancel = f.below(2) == 1;
    f.fill(ci.collision_point_m);
    f.fill(ci.support_point_m);
    ci.time_to_collision_s = f.real();
    EXPECT_TRUE(round_trip(ci) == ci);

    msg::UgvStatus st;
    st.stamp = f.stamp();
    st.ugv_id = f.u16();
    st.mode = static_cast<msg::UgvMode>(f.below(6));
    f.fill(st.position_m);
    st.yaw_rad = f.real();
    f.fill(st.covariance);
    st.velocity_mps = f.real();
    st.yaw_rate_radps = f.real();
    f.fill(st.goal_m);
    st.waiting_time_s = f.real();
    st.rejected_inputs = f.u32();
    st.overruns = f.u32();
    st.degradation = static_cast<std::uint8_t>(f.below(3));
    EXPECT_TRUE(round_trip(st) == st);

    msg::SupportPlan sp;
    sp.stamp = f.stamp();
    sp.uav_id = f.u16();
    sp.seq = f.u32();
    sp.total_lateness_s = f.real();
    sp.stop_count = static_cast<std::uint16_t>(f.below(limits::kMaxSupportRequests + 1));
    for (std::size_t i = 0; i < sp.stop_count; ++i) {
      sp.stops[i].ugv_id = f.u16();
      f.fill(sp.stops[i].point_m);
      sp.stops[i].eta_s = f.real();
      sp.stops[i].deadline_s = f.real();
    }
    EXPECT_TRUE(round_trip(sp) == sp);
  }
}

TEST(DdsConvert, MapPatchPayloadIsBorrowedNotCopiedAndClamped) {
  msg::MapPatch mp;
  mp.data_bytes = 5000;  // corrupt length: never read past the array
  IdlSample<msg::MapPatch> idl;
  to_idl(mp, idl);
  EXPECT_EQ(idl.sample.data._buffer, mp.data);
  EXPECT_EQ(idl.sample.data._length, limits::kMaxPatchBytes);
  EXPECT_FALSE(idl.sample.data._release);
}

TEST(DdsConvert, RejectsWhatTheStructCannotHold) {
  std::uint8_t big[limits::kMaxPatchBytes + 1] = {};
  colag_idl_MapPatch mp{};
  mp.data._buffer = big;
  mp.data._length = limits::kMaxPatchBytes + 1;
  msg::MapPatch out;
  EXPECT_EQ(from_idl(mp, out).code(), Errc::kInvalidArgument);
  mp.data._length = 4;
  mp.encoding = 7;
  EXPECT_EQ(from_idl(mp, out).code(), Errc::kInvalidArgument);
  mp.encoding = 1;
  mp.data._buffer = nullptr;  // length without a buffer
  EXPECT_EQ(from_idl(mp, out).code(), Errc::kInvalidArgument);

  colag_idl_UgvStatus st{};
  st.mode = 99;
  msg::UgvStatus st_out;
  EXPECT_EQ(from_idl(st, st_out).code(), Errc::kInvalidArgument);

  colag_idl_SupportStop stops[limits::kMaxSupportRequests + 1] = {};
  colag_idl_SupportPlan sp{};
  sp.stops._buffer = stops;
  sp.stops._length = limits::kMaxSupportRequests + 1;
  msg::SupportPlan sp_out;
  EXPECT_EQ(from_idl(sp, sp_out).code(), Errc::kInvalidArgument);
}
