// The offboard protocol with PX4 (arming, offboard, acknowledgements, failsafes, landing),
// driven step by step against a scripted PX4.
#include "colag/hal/px4/offboard_sequencer.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace colag;
using namespace colag::hal::px4;
using namespace std::chrono_literals;
using State = OffboardSequencer::State;

namespace {

// A PX4 that acknowledges what it is told (or not), and whose status the test sets.
struct Px4Script {
  bool answer = true;
  std::uint8_t result = kAckAccepted;
  bool obey = true;  // an accepted command shows in the status
  bool silent = false;
  Px4Status status;
  std::vector<Px4Command> received;
};

struct Rig {
  OffboardSequencer seq;
  Px4Script px4;
  TimePoint now{};
  bool setpoints = true;

  explicit Rig(const OffboardConfig& c = {}) : seq(c) {}
  // Runs for `d` at 50 Hz: setpoints, PX4's 10 Hz status, its acknowledgements.
  void run(Duration d) {
    const TimePoint end = now + d;
    int tick = 0;
    while (now < end) {
      now += 20ms;
      if (setpoints) seq.on_setpoint(now);
      if (!px4.silent && ++tick % 5 == 0) seq.on_status(now, px4.status);
      Px4Command c;
      if (seq.step(now, c)) {
        px4.received.push_back(c);
        if (px4.answer && !px4.silent) seq.on_ack(now, c.command, px4.result);
        if (px4.obey && px4.result == kAckAccepted) {
          if (c.command == kCmdDoSetMode) px4.status.nav_state = kNavStateOffboard;
          if (c.command == kCmdArmDisarm) px4.status.armed = c.param1 == 1.0F;
          if (c.command == kCmdNavLand) px4.status.nav_state = 18;
        }
      }
    }
  }
  int sent(std::uint32_t command) const {
    int n = 0;
    for (const Px4Command& c : px4.received)
      n += c.command == command ? 1 : 0;
    return n;
  }
};

}  // namespace

TEST(OffboardSequencer, PrimesAsksForOffboardThenArmsAndIsInControl) {
  Rig rig;
  rig.px4.status.nav_state = 2;  // position mode, disarmed, on the ground
  rig.run(900ms);
  EXPECT_TRUE(rig.px4.received.empty());  // first a second of stream: PX4 wants it fresh
  EXPECT_TRUE(rig.seq.streaming(rig.now));
  EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kStarting);
  rig.run(1s);
  ASSERT_EQ(rig.px4.received.size(), 2u);
  EXPECT_EQ(rig.px4.received[0].command, kCmdDoSetMode);
  EXPECT_EQ(rig.px4.received[0].param1, kModeCustom);
  EXPECT_EQ(rig.px4.received[0].param2, kMainModeOffboard);
  EXPECT_EQ(rig.px4.received[1].command, kCmdArmDisarm);
  EXPECT_EQ(rig.px4.received[1].param1, 1.0F);
  rig.run(300ms);  // the next status shows armed in offboard
  EXPECT_EQ(rig.seq.state(), State::kInControl);
  EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kInControl);
  EXPECT_TRUE(rig.seq.streaming(rig.now));
}

TEST(OffboardSequencer, WaitsForPx4AndASetpointAndSaysWhyItWaits) {
  Rig rig;
  rig.px4.silent = true;
  rig.run(3s);
  EXPECT_EQ(rig.seq.state(), State::kWaitingForPx4);
  EXPECT_EQ(rig.seq.status().fault, msg::FlightFault::kSilent);
  EXPECT_FALSE(rig.seq.streaming(rig.now));
  rig.seq.set_wrong_release(true);
  rig.run(100ms);
  EXPECT_EQ(rig.seq.status().fault, msg::FlightFault::kWrongRelease);
  // PX4 heard but no setpoint yet (no odometry): nothing is asked of it.
  Rig no_setpoint;
  no_setpoint.setpoints = false;
  no_setpoint.run(5s);
  EXPECT_EQ(no_setpoint.seq.state(), State::kWaitingForPx4);
  EXPECT_TRUE(no_setpoint.px4.received.empty());
}

TEST(OffboardSequencer, AnUnansweredCommandIsRetriedThenReported) {
  Rig rig;
  rig.px4.answer = false;
  rig.px4.obey = false;
  rig.run(10s);
  EXPECT_EQ(rig.sent(kCmdDoSetMode), OffboardConfig{}.command_attempts);
  EXPECT_EQ(rig.sent(kCmdArmDisarm), 0);
  EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kLost);
  EXPECT_EQ(rig.seq.status().fault, msg::FlightFault::kNoAck);
  EXPECT_FALSE(rig.seq.streaming(rig.now));
}

TEST(OffboardSequencer, ARefusedCommandEndsTheTakeOff) {
  Rig rig;
  rig.px4.result = 2;  // denied (pre-flight checks failing, say)
  rig.run(3s);
  EXPECT_EQ(rig.sent(kCmdDoSetMode), 1);
  EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kLost);
  EXPECT_EQ(rig.seq.status().fault, msg::FlightFault::kRefused);
}

TEST(OffboardSequencer, LosingPx4InFlightIsDetectedWithinTheSilenceTimeout) {
  Rig rig;
  rig.run(3s);
  ASSERT_EQ(rig.seq.state(), State::kInControl);
  rig.px4.silent = true;
  rig.run(OffboardConfig{}.silence_timeout + 120ms);  // its last status was <= 100 ms old
  EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kLost);
  EXPECT_EQ(rig.seq.status().fault, msg::FlightFault::kSilent);
  EXPECT_FALSE(rig.seq.streaming(rig.now));
  rig.px4.silent = false;  // back, but never taken back
  rig.run(3s);
  EXPECT_EQ(rig.seq.state(), State::kLost);
}

TEST(OffboardSequencer, AFailsafeAnotherModeOrADisarmEndsControlWithTheReason) {
  struct Case {
    const char* what;
    void (*apply)(Px4Status&);
    msg::FlightFault fault;
  };
  const Case cases[] = {
      {"failsafe", [](Px4Status& s) { s.failsafe = true; }, msg::FlightFault::kFailsafe},
      {"position mode", [](Px4Status& s) { s.nav_state = 2; }, msg::FlightFault::kLeftOffboard},
      {"disarmed", [](Px4Status& s) { s.armed = false; }, msg::FlightFault::kDisarmed},
  };
  for (const Case& c : cases) {
    Rig rig;
    rig.run(3s);
    ASSERT_EQ(rig.seq.state(), State::kInControl) << c.what;
    c.apply(rig.px4.status);
    rig.run(120ms);  // its next status
    EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kLost) << c.what;
    EXPECT_EQ(rig.seq.status().fault, c.fault) << c.what;
    EXPECT_FALSE(rig.seq.streaming(rig.now)) << c.what;
  }
}

TEST(OffboardSequencer, SetpointsThatStopStopTheStreamSoPx4FailsSafe) {
  Rig rig;
  rig.run(3s);
  ASSERT_EQ(rig.seq.state(), State::kInControl);
  rig.setpoints = false;  // the supervisor lost its odometry
  rig.run(600ms);
  EXPECT_FALSE(rig.seq.streaming(rig.now));
}

TEST(OffboardSequencer, LandsAtTheEndAndIsLandedOnceDisarmed) {
  Rig rig;
  rig.run(3s);
  ASSERT_EQ(rig.seq.state(), State::kInControl);
  rig.seq.land(rig.now);
  rig.run(200ms);
  EXPECT_EQ(rig.sent(kCmdNavLand), 1);
  EXPECT_EQ(rig.seq.status().state, msg::UavFlight::kLanding);
  EXPECT_FALSE(rig.seq.streaming(rig.now));
  EXPECT_EQ(rig.seq.state(), State::kLanding);
  rig.px4.status.armed = false;  // PX4 disarms itself on the ground
  rig.run(200ms);
  EXPECT_EQ(rig.seq.state(), State::kLanded);
  // A lost aircraft is not commanded, not even to land: a pilot or its failsafe has it.
  Rig lost;
  lost.run(3s);
  lost.px4.status.failsafe = true;
  lost.run(200ms);
  ASSERT_EQ(lost.seq.state(), State::kLost);
  lost.seq.land(lost.now);
  lost.run(1s);
  EXPECT_EQ(lost.sent(kCmdNavLand), 0);
}
