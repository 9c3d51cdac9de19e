#include <gtest/gtest.h>

#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"

using namespace colag;
using namespace colag::hal;
using namespace colag::hal::can;
using namespace std::chrono_literals;

namespace {
const WheelProtocolConfig kProto;
const WheelGeometry kGeo;
double m_per_tick() {
  return 2.0 * M_PI * kGeo.wheel_radius_m / kGeo.ticks_per_revolution;
}

CanFrame counts(std::uint32_t l, std::uint32_t r, std::uint8_t alive, TimePoint t) {
  CanFrame f = encode(EncoderCounts{l, r, alive}, kProto);
  f.stamp = t;
  return f;
}
}  // namespace

TEST(WheelProtocol, Crc8IsSaeJ1850) {
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc8(check, 9), 0x4B);  // the catalogued check value of CRC-8/SAE-J1850
}

TEST(WheelProtocol, EveryMessageRoundTrips) {
  for (std::uint32_t v : {0u, 1u, 0x7FFFFFu, 0x800000u, 0xFFFFFFu, 123456u}) {
    DecodedFrame d;
    ASSERT_EQ(decode(encode(EncoderCounts{v, 0xFFFFFFu - v, 7}, kProto), kProto, d),
              DecodeError::kNone);
    EXPECT_EQ(d.kind, FrameKind::kCounts);
    EXPECT_EQ(d.counts.left_ticks, v);
    EXPECT_EQ(d.counts.right_ticks, 0xFFFFFFu - v);
    EXPECT_EQ(d.counts.alive, 7);
  }
  for (std::int16_t v :
       {std::int16_t{0}, std::int16_t{-32768}, std::int16_t{32767}, std::int16_t{-512}}) {
    DecodedFrame d;
    ASSERT_EQ(
        decode(encode(WheelSpeeds{v, static_cast<std::int16_t>(-v - 1), 3}, kProto), kProto, d),
        DecodeError::kNone);
    EXPECT_EQ(d.speeds.left_mmps, v);
    ASSERT_EQ(decode(encode(SpeedCommand{v, v, true, 9}, kProto), kProto, d), DecodeError::kNone);
    EXPECT_EQ(d.kind, FrameKind::kCommand);
    EXPECT_EQ(d.command.right_mmps, v);
    EXPECT_TRUE(d.command.enable);
  }
}

TEST(WheelProtocol, RejectsWrongIdDlcChecksumAndEveryFlippedBit) {
  const CanFrame good = encode(EncoderCounts{1000, 2000, 1}, kProto);
  DecodedFrame d;
  CanFrame f = good;
  f.id = 0x123;
  EXPECT_EQ(decode(f, kProto, d), DecodeError::kUnknownId);
  f = good;
  f.extended = true;
  EXPECT_EQ(decode(f, kProto, d), DecodeError::kUnknownId);
  f = good;
  f.dlc = 7;
  EXPECT_EQ(decode(f, kProto, d), DecodeError::kWrongDlc);
  // CRC-8 catches every single-bit error.
  for (int byte = 0; byte < 8; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      f = good;
      f.data[byte] ^= static_cast<std::uint8_t>(1 << bit);
      EXPECT_EQ(decode(f, kProto, d), DecodeError::kBadChecksum) << byte << "." << bit;
    }
  }
}

TEST(WheelProtocol, TickDeltaTakesTheShortWayAroundTheWrap) {
  EXPECT_EQ(tick_delta(100, 150), 50);
  EXPECT_EQ(tick_delta(150, 100), -50);
  EXPECT_EQ(tick_delta(0xFFFFF0u, 0x000010u), 32);   // forward through the wrap
  EXPECT_EQ(tick_delta(0x000010u, 0xFFFFF0u), -32);  // backward through the wrap
}

TEST(CanWheelOdometry, TicksBecomeTwistAcrossTheWrap) {
  scripted::ScriptedCanBus bus;
  CanWheelOdometry odo(bus, kProto, kGeo);
  // Straight at 0.5 m/s for 20 ms: 0.01 m per wheel; then a turn on the spot.
  const auto ticks = static_cast<std::uint32_t>(std::lround(0.01 / m_per_tick()));
  const std::uint32_t start = kTickModulus - ticks / 2;  // the left counter wraps in between
  ASSERT_TRUE(bus.inject(counts(start, 5000, 0, TimePoint{1000ms})));
  ASSERT_TRUE(
      bus.inject(counts((start + ticks) % kTickModulus, 5000 + ticks, 1, TimePoint{1020ms})));
  ASSERT_TRUE(bus.inject(
      counts((start + ticks - 100) % kTickModulus, 5000 + ticks + 100, 2, TimePoint{1040ms})));
  WheelOdometrySample s;
  ASSERT_TRUE(odo.poll(s));
  EXPECT_NEAR(s.v_mps, 0.5, 0.002);
  EXPECT_NEAR(s.omega_radps, 0.0, 1e-9);
  EXPECT_EQ(s.stamp, TimePoint{1020ms});
  ASSERT_TRUE(odo.poll(s));
  EXPECT_NEAR(s.v_mps, 0.0, 1e-9);
  EXPECT_NEAR(s.omega_radps, 200 * m_per_tick() / kGeo.track_width_m / 0.02, 1e-9);
  EXPECT_FALSE(odo.poll(s));
  EXPECT_EQ(odo.last_sample_time(), TimePoint{1040ms});
}

TEST(CanWheelOdometry, CountsLostDuplicateCorruptAndImplausibleFrames) {
  scripted::ScriptedCanBus bus;
  CanWheelOdometry odo(bus, kProto, kGeo);
  ASSERT_TRUE(bus.inject(counts(0, 0, 10, TimePoint{0ms})));
  ASSERT_TRUE(bus.inject(counts(100, 100, 13, TimePoint{60ms})));  // frames 11, 12 lost
  ASSERT_TRUE(bus.inject(counts(100, 100, 13, TimePoint{60ms})));  // duplicated
  CanFrame bad = counts(200, 200, 14, TimePoint{80ms});
  bad.data[2] ^= 0x40;
  ASSERT_TRUE(bus.inject(bad));
  CanFrame short_frame = counts(200, 200, 14, TimePoint{80ms});
  short_frame.dlc = 4;
  ASSERT_TRUE(bus.inject(short_frame));
  CanFrame other = counts(200, 200, 14, TimePoint{80ms});
  other.id = 0x555;
  ASSERT_TRUE(bus.inject(other));
  ASSERT_TRUE(bus.inject(counts(5'000'000, 200, 14, TimePoint{80ms})));   // a jump no wheel makes
  ASSERT_TRUE(bus.inject(counts(5'000'100, 300, 15, TimePoint{100ms})));  // fine again
  WheelOdometrySample s;
  int samples = 0;
  while (odo.poll(s))
    ++samples;
  const auto& c = odo.counters();
  EXPECT_EQ(samples, 2);  // 0->13 (over the gap, 60 ms) and 14->15
  EXPECT_EQ(c.lost_frames, 2u);
  EXPECT_EQ(c.duplicates, 1u);
  EXPECT_EQ(c.bad_checksum, 1u);
  EXPECT_EQ(c.wrong_dlc, 1u);
  EXPECT_EQ(c.unknown_id, 1u);
  EXPECT_EQ(c.implausible, 1u);
}

// Found by fuzz_can_frames: two frames stamped 1 us apart made 100 ticks a 150 m/s sample.
TEST(CanWheelOdometry, FramesStampedTooCloseAreImplausibleNotFast) {
  scripted::ScriptedCanBus bus;
  CanWheelOdometry odo(bus, kProto, kGeo);
  ASSERT_TRUE(bus.inject(counts(0, 0, 1, TimePoint{20ms})));
  ASSERT_TRUE(bus.inject(counts(100, 100, 2, TimePoint{20ms + 1us})));
  ASSERT_TRUE(bus.inject(counts(200, 200, 3, TimePoint{40ms})));  // 100 ticks in ~20 ms: fine
  WheelOdometrySample s;
  ASSERT_TRUE(odo.poll(s));
  EXPECT_NEAR(s.v_mps, 100 * m_per_tick() / (0.02 - 1e-6), 1e-9);
  EXPECT_FALSE(odo.poll(s));
  EXPECT_EQ(odo.counters().implausible, 1u);
}

TEST(CanDrive, TwistBecomesWheelSpeedsWithinTheLimit) {
  scripted::ScriptedCanBus bus;
  CanDrive drive(bus, kProto, kGeo);
  ASSERT_TRUE(drive.command({TimePoint{1s}, 0.4, 0.5}));
  DecodedFrame d;
  ASSERT_EQ(decode(bus.sent().back(), kProto, d), DecodeError::kNone);
  EXPECT_EQ(d.command.left_mmps, 300);  // 0.4 - 0.2 * 0.5
  EXPECT_EQ(d.command.right_mmps, 500);
  EXPECT_TRUE(d.command.enable);
  // Too fast for one wheel: both are scaled, so the robot still turns on the same arc.
  ASSERT_TRUE(drive.command({TimePoint{1s}, 0.6, 1.0}));
  ASSERT_EQ(decode(bus.sent().back(), kProto, d), DecodeError::kNone);
  EXPECT_EQ(d.command.right_mmps, 700);
  EXPECT_EQ(d.command.left_mmps, 350);  // 0.4 * 700/800
  // NaN: refused, and the robot is stopped.
  EXPECT_FALSE(drive.command({TimePoint{1s}, std::numeric_limits<double>::quiet_NaN(), 0.0}));
  ASSERT_EQ(decode(bus.sent().back(), kProto, d), DecodeError::kNone);
  EXPECT_EQ(d.command.left_mmps, 0);
  EXPECT_EQ(d.command.right_mmps, 0);
}
