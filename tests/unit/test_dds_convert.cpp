// Message struct <-> IDL sample mapping: every field of every type survives the round trip,
// and what the struct cannot hold is rejected.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "colag/common/random.hpp"
#include "colag/hal/ros2/cdr.hpp"
#include "colag/msg/wire_size.hpp"
#include "colag/platform/dds/convert.hpp"

using namespace colag;
using namespace colag::platform::dds;

namespace {

// Fills any message field with random values, from the field lists (msg::Fields): a new
// message is covered without a line here.
class Filler {
 public:
  explicit Filler(std::uint64_t seed) : rng_(seed) {}
  template <class T>
  void fill(T& v) {
    if constexpr (std::is_array_v<T>) {
      for (auto& e : v)
        fill(e);
    } else if constexpr (std::is_same_v<T, TimePoint>) {
      v = TimePoint{Duration{static_cast<std::int64_t>(rng_.next_u64() >> 1)}};
    } else if constexpr (std::is_same_v<T, bool>) {
      v = rng_.below(2) == 1;
    } else if constexpr (std::is_enum_v<T>) {
      const auto last = static_cast<std::uint64_t>(msg::EnumRange<T>::kLast);
      v = static_cast<T>(rng_.below(last + 1));
    } else if constexpr (std::is_floating_point_v<T>) {
      v = static_cast<T>(rng_.uniform(-100.0, 100.0));
    } else if constexpr (std::is_integral_v<T>) {
      v = static_cast<T>(rng_.next_u64());
    } else if constexpr (msg::kIsSequence<T>) {
      v.count = static_cast<std::uint16_t>(rng_.below(T::kCapacity + 1));
      for (auto& e : v)
        fill(e);
    } else {
      msg::for_each_field(v, [&](std::string_view, auto& field) { fill(field); });
    }
  }

 private:
  Rng rng_;
};

template <class T>
bool differs(const T& a, const T& b) {
  if constexpr (std::is_array_v<T>) {
    for (std::size_t i = 0; i < std::extent_v<T>; ++i)
      if (differs(a[i], b[i])) return true;
    return false;
  } else {
    return !(a == b);
  }
}

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
  int types = 0;
  msg::for_each_message_type([&]<class Msg>() {
    ++types;
    for (int trial = 0; trial < 200; ++trial) {
      auto m = std::make_unique<Msg>();
      f.fill(*m);
      EXPECT_TRUE(round_trip(*m) == *m) << msg::Fields<Msg>::kType << " trial " << trial;
    }
  });
  EXPECT_EQ(types, static_cast<int>(msg::kTopicCount));
}

// Over the trials every field takes a value other than its default: were a field not carried,
// the round trip above would bring back its default and fail. Checked so that it cannot pass
// vacuously.
TEST(DdsConvert, TheRandomSamplesSetEveryField) {
  Filler f(2024);
  msg::for_each_message_type([&]<class Msg>() {
    constexpr std::size_t kFields = msg::Fields<Msg>::kNames.size();
    std::array<bool, kFields> seen{};
    const Msg plain{};
    for (int trial = 0; trial < 200; ++trial) {
      auto m = std::make_unique<Msg>();
      f.fill(*m);
      auto set = msg::Fields<Msg>::tie(*m);
      auto unset = msg::Fields<Msg>::tie(plain);
      [&]<std::size_t... I>(std::index_sequence<I...>) {
        ((seen[I] = seen[I] || differs(std::get<I>(set), std::get<I>(unset))), ...);
      }
      (std::make_index_sequence<kFields>{});
    }
    for (std::size_t i = 0; i < kFields; ++i)
      EXPECT_TRUE(seen[i]) << msg::Fields<Msg>::kType << "." << msg::Fields<Msg>::kNames[i];
  });
}

// The simulator counts each robot's traffic with msg::wire_bytes: it must be what Cyclone's
// serializer makes of the sample, for every message, full or empty.
TEST(DdsConvert, WireBytesAreWhatCycloneSerialises) {
  Filler f(7);
  msg::for_each_message_type([&]<class Msg>() {
    for (int trial = 0; trial < 50; ++trial) {
      auto m = std::make_unique<Msg>();
      if (trial > 0) f.fill(*m);
      IdlSample<Msg> idl;
      to_idl(*m, idl);
      std::vector<std::uint8_t> cdr;
      ASSERT_TRUE(hal::ros2::to_cdr(&idl.sample, descriptor<Msg>(), cdr));
      EXPECT_EQ(msg::wire_bytes(*m), cdr.size()) << msg::Fields<Msg>::kType << " trial " << trial;
    }
  });
}

TEST(DdsConvert, MapPatchPayloadIsBorrowedNotCopiedAndClamped) {
  msg::MapPatch mp;
  mp.data.count = 5000;  // corrupt length: never read past the array
  IdlSample<msg::MapPatch> idl;
  to_idl(mp, idl);
  EXPECT_EQ(idl.sample.data._buffer, mp.data.items);
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

  // A boolean byte other than 0 or 1 (the fuzzer's find: reading it as a bool is undefined).
  colag_idl_CollisionInfo ci{};
  const unsigned char two = 2;
  std::memcpy(&ci.cancel, &two, 1);
  msg::CollisionInfo ci_out;
  EXPECT_EQ(from_idl(ci, ci_out).code(), Errc::kInvalidArgument);
  const unsigned char one = 1;
  std::memcpy(&ci.cancel, &one, 1);
  ASSERT_TRUE(from_idl(ci, ci_out).is_ok());
  EXPECT_TRUE(ci_out.cancel);
}
