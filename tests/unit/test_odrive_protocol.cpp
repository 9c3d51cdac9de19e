// ODrive CAN Simple: ids, payload layouts and the protocol's published example frames.
#include "colag/hal/can/odrive_protocol.hpp"

#include <gtest/gtest.h>

#include <cstring>

using namespace colag::hal;
using namespace colag::hal::can::odrive;

namespace {

CanFrame from_bytes(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  CanFrame f;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), f.data);
  return f;
}

}  // namespace

TEST(OdriveProtocol, IdsAreNodeShiftedFiveOrCommand) {
  EXPECT_EQ(can_id(1, Command::kSetInputVel), 0x02Du);
  EXPECT_EQ(can_id(3, Command::kHeartbeat), 0x061u);
  EXPECT_EQ(can_id(kMaxNodeId, Command::kClearErrors), 0x7F8u);
  EXPECT_TRUE(is_valid(set_input_vel(kMaxNodeId, 1.0F, 0.0F)));
}

TEST(OdriveProtocol, SetInputVelMatchesThePublishedExample) {
  // Node 1, velocity -2.5 turns/s, torque feed-forward 0.25 N m.
  const CanFrame f = set_input_vel(1, -2.5F, 0.25F);
  EXPECT_EQ(f.id, 0x02Du);
  ASSERT_EQ(f.dlc, 8);
  const std::uint8_t expected[8] = {0x00, 0x00, 0x20, 0xc0, 0x00, 0x00, 0x80, 0x3e};
  EXPECT_EQ(std::memcmp(f.data, expected, 8), 0);
}

TEST(OdriveProtocol, CommandsCarryTheirValuesLittleEndian) {
  CanFrame f = set_axis_state(2, kAxisStateClosedLoop);
  EXPECT_EQ(f.id, can_id(2, Command::kSetAxisState));
  ASSERT_EQ(f.dlc, 4);
  EXPECT_EQ(f.data[0], 8);
  EXPECT_EQ(f.data[1] | f.data[2] | f.data[3], 0);
  f = set_controller_mode(2, kControlModeVelocity, kInputModeVelRamp);
  ASSERT_EQ(f.dlc, 8);
  EXPECT_EQ(f.data[0], 2);
  EXPECT_EQ(f.data[4], 2);
  EXPECT_EQ(estop(2).dlc, 0);
  EXPECT_EQ(clear_errors(2).id, can_id(2, Command::kClearErrors));
}

TEST(OdriveProtocol, DecodesHeartbeatsAndEncoderEstimatesOfItsNodeOnly) {
  Feedback fb;
  // Axis error 0x80000001, closed loop, the encoder error flag set.
  ASSERT_EQ(decode(from_bytes(0x021, {0x01, 0x00, 0x00, 0x80, 0x08, 0x00, 0x01, 0x00}), 1, fb),
            DecodeError::kNone);
  EXPECT_EQ(fb.command, Command::kHeartbeat);
  EXPECT_EQ(fb.heartbeat.axis_error, 0x80000001u);
  EXPECT_EQ(fb.heartbeat.axis_state, kAxisStateClosedLoop);
  EXPECT_FALSE(fb.heartbeat.motor_error);
  EXPECT_TRUE(fb.heartbeat.encoder_error);
  EXPECT_FALSE(fb.heartbeat.controller_error);
  // Estimates: pos 1.5 turns, vel -0.25 turns/s.
  const CanFrame est = from_bytes(0x029, {0x00, 0x00, 0xc0, 0x3f, 0x00, 0x00, 0x80, 0xbe});
  ASSERT_EQ(decode(est, 1, fb), DecodeError::kNone);
  EXPECT_EQ(fb.command, Command::kEncoderEstimates);
  EXPECT_FLOAT_EQ(fb.estimates.pos_turns, 1.5F);
  EXPECT_FLOAT_EQ(fb.estimates.vel_turns_per_s, -0.25F);
  // Another node's, a command, a short frame, an extended id: refused with the reason.
  EXPECT_EQ(decode(est, 2, fb), DecodeError::kOtherNode);
  EXPECT_EQ(decode(set_input_vel(1, 1.0F, 0.0F), 1, fb), DecodeError::kNotFeedback);
  EXPECT_EQ(decode(from_bytes(0x029, {0x00, 0x00}), 1, fb), DecodeError::kWrongDlc);
  CanFrame ext = est;
  ext.extended = true;
  EXPECT_EQ(decode(ext, 1, fb), DecodeError::kExtendedId);
}
