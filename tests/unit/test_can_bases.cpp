// The UGV's base drivers (ODrive, AgileX V2; ours is test_can_wheel.cpp) against the emulators of
// the devices (colag::sim::BaseEmulator inside a UgvBody) over the simulated CAN link: start-up,
// driving, odometry, and every fault path (device errors, e-stop, silence, the device's watchdog,
// bus-off), each turned into a zero-speed command and a health report.
#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.hpp"
#include "colag/hal/can/agilex_protocol.hpp"
#include "colag/hal/can/can_base.hpp"
#include "colag/hal/can/odrive_protocol.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/hal/sim/can_link.hpp"
#include "colag/sim/world/ugv_body.hpp"

using namespace colag;
using namespace colag::hal;
using namespace colag::hal::can;
using namespace std::chrono_literals;

namespace {

scripted::ManualClock start_clock() {
  scripted::ManualClock c;
  c.set(TimePoint{1s});
  return c;
}

struct Rig {
  explicit Rig(BaseProtocol p, const BaseConfig& base = {}) : config(make(p, base)) {}
  static colag::sim::UgvBodyConfig make(BaseProtocol p, BaseConfig base) {
    base.protocol = p;
    colag::sim::UgvBodyConfig c;
    c.base = base;
    c.motion_noise_fraction = 0.0;
    c.odometry_noise.sigma_v_mps = c.odometry_noise.sigma_omega_radps = 0.0;
    return c;
  }

  // One 20 ms period: the driver commands, the base moves and reports, the driver reads.
  void step(double v, double omega, bool body_reports = true) {
    if (drive_on) (void)driver.drive().command({clock.now(), v, omega});
    if (body_reports) {
      body.step(clock.now(), 0.02, link.motor());
    } else {
      CanFrame f;
      while (link.motor().receive(f)) {
      }
    }
    clock.advance(20ms);
    WheelOdometrySample s;
    while (driver.odometry().poll(s)) {
      last = s;
      distance_m += s.v_mps * 0.02;
      ++samples;
    }
  }
  void run(double seconds_, double v, double omega = 0.0) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds_ / 0.02)); ++k)
      step(v, omega);
  }
  DriveHealth health() { return driver.drive().health(); }

  colag::sim::UgvBodyConfig config;
  scripted::ManualClock clock = start_clock();
  hal::sim::SimCanLink link{clock};
  colag::sim::UgvBody body{config, Pose2{}, 1};
  CanBase driver{link.board(), config.base, config.geometry};
  bool drive_on = true;
  WheelOdometrySample last;
  double distance_m = 0.0;
  int samples = 0;
};

}  // namespace

TEST(OdriveBase, EntersClosedLoopDrivesAndMeasuresTheWheels) {
  Rig rig(BaseProtocol::kOdrive);
  rig.run(3.0, 0.4);
  EXPECT_TRUE(rig.body.controller().driving());
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kNone);
  EXPECT_NEAR(rig.body.speed_mps(), 0.4, 1e-3);
  EXPECT_NEAR(rig.last.v_mps, 0.4, 0.01);
  // Its odometry is the wheels' travel (the right axis mirrored: -1 in the default config).
  EXPECT_NEAR(rig.distance_m, rig.body.travelled_m(), 0.02);
  EXPECT_GT(rig.samples, 100);
  // A turn: the same sign in the command, the body and the odometry.
  rig.run(1.0, 0.0, 0.5);
  EXPECT_GT(rig.body.pose().yaw_rad, 0.2);
  EXPECT_NEAR(rig.last.omega_radps, 0.5, 0.02);
}

TEST(OdriveBase, GearRatioAndNodeIdsAreThoseConfigured) {
  BaseConfig b;
  b.odrive.left = {5, -1};
  b.odrive.right = {9, 1};
  b.odrive.motor_turns_per_wheel_turn = 8.0;
  Rig rig(BaseProtocol::kOdrive, b);
  rig.run(3.0, 0.3);
  EXPECT_NEAR(rig.body.speed_mps(), 0.3, 1e-3);
  EXPECT_NEAR(rig.last.v_mps, 0.3, 0.01);
  // The velocity input itself: left node 5, mirrored, 8 motor turns per wheel turn.
  (void)rig.driver.drive().command({rig.clock.now(), 0.3, 0.0});
  CanFrame f;
  bool seen = false;
  while (rig.link.motor().receive(f)) {
    odrive::CommandFrame c;
    if (odrive::decode_command(f, 5, c) == odrive::DecodeError::kNone &&
        c.command == odrive::Command::kSetInputVel) {
      EXPECT_NEAR(c.vel_turns_per_s, -0.3 / (2 * M_PI * 0.05) * 8.0, 1e-4);
      seen = true;
    }
  }
  EXPECT_TRUE(seen);
}

TEST(OdriveBase, AnAxisErrorIsAMotorFaultAndZeroSpeedThatStaysLatched) {
  Rig rig(BaseProtocol::kOdrive);
  rig.run(2.0, 0.4);
  rig.body.controller().set_fault(true);
  rig.run(0.2, 0.4);  // the next heartbeat (100 ms) says so
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kMotorError);
  EXPECT_EQ(rig.health().code, odrive::kAxisErrorMotorFailed);
  rig.body.controller().set_fault(false);
  rig.run(2.0, 0.4);  // asked to drive on: the driver sends zero and does not clear the error
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kMotorError);
  EXPECT_NEAR(rig.body.speed_mps(), 0.0, 1e-9);
}

TEST(OdriveBase, ASilentHostTripsTheAxesWatchdogAndTheLiveHostClearsIt) {
  Rig rig(BaseProtocol::kOdrive);
  rig.run(2.0, 0.4);
  rig.drive_on = false;  // ugv_fw stalls: no more velocity inputs
  rig.run(1.0, 0.4);     // its 200 ms watchdog, then the wheels brake
  EXPECT_FALSE(rig.body.controller().driving());
  EXPECT_NEAR(rig.body.speed_mps(), 0.0, 1e-9);
  // Live again, the driver clears the trip (it says only that this host fell silent): the axes
  // are not ready in this step, then drive on.
  rig.drive_on = true;
  rig.step(0.4, 0.0);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kNotReady);
  rig.run(1.0, 0.4);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kNone);
  EXPECT_NEAR(rig.body.speed_mps(), 0.4, 1e-3);
  EXPECT_EQ(rig.driver.counters().recoveries, 2u);  // one per axis
}

TEST(OdriveBase, ARestartClearsTheLastRunsErrorsEvenIfTheFirstClearIsLost) {
  Rig rig(BaseProtocol::kOdrive);
  rig.run(2.0, 0.4);
  rig.body.controller().set_fault(true);  // a motor error latched in the last run
  rig.run(0.2, 0.4);
  rig.body.controller().set_fault(false);
  rig.drive_on = false;
  rig.run(0.5, 0.0);
  // ugv_fw started again; its first frames are lost (the bus not up yet).
  CanBase restarted(rig.link.board(), rig.config.base, rig.config.geometry);
  auto step = [&](bool link_down) {
    rig.link.set_down(link_down);
    (void)restarted.drive().command({rig.clock.now(), 0.4, 0.0});
    rig.link.set_down(false);
    rig.body.step(rig.clock.now(), 0.02, rig.link.motor());
    rig.clock.advance(20ms);
    WheelOdometrySample s;
    while (restarted.odometry().poll(s)) {
    }
  };
  step(true);
  for (int k = 0; k < 100; ++k)
    step(false);
  EXPECT_EQ(restarted.drive().health().fault, msg::BaseFault::kNone);
  EXPECT_NEAR(rig.body.speed_mps(), 0.4, 1e-3);
  EXPECT_EQ(restarted.counters().recoveries, 0u);  // clears at start are not recoveries
}

TEST(OdriveBase, AfterStartOnlyTheWatchdogsErrorIsClearedNotAMotorError) {
  Rig rig(BaseProtocol::kOdrive);
  rig.run(4.0, 0.4);  // past the start phase
  rig.body.controller().set_fault(true);
  rig.run(0.2, 0.4);
  rig.body.controller().set_fault(false);
  rig.run(3.0, 0.4);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kMotorError);
  EXPECT_EQ(rig.driver.counters().recoveries, 0u);
}

TEST(OdriveBase, LostHeartbeatsAreASilentBaseAndShutdownIdlesTheAxes) {
  Rig rig(BaseProtocol::kOdrive);
  rig.run(2.0, 0.4);
  for (int k = 0; k < 20; ++k)
    rig.step(0.4, 0.0, false);  // the axes fall silent (power cut, cable)
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kBaseSilent);
  rig.run(1.0, 0.0);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kNone);
  rig.driver.drive().shutdown(rig.clock.now());
  rig.body.step(rig.clock.now(), 0.02, rig.link.motor());
  EXPECT_FALSE(rig.body.controller().driving());
}

TEST(AgilexBase, SelectsCanModeDrivesAndMeasuresTheSides) {
  Rig rig(BaseProtocol::kAgilexV2);
  rig.run(3.0, 0.5);
  EXPECT_TRUE(rig.body.controller().driving());
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kNone);
  EXPECT_NEAR(rig.body.speed_mps(), 0.5, 1e-3);
  EXPECT_NEAR(rig.last.v_mps, 0.5, 0.05);  // 1 mm odometry steps over 20 ms
  EXPECT_NEAR(rig.distance_m, rig.body.travelled_m(), 0.02);
  rig.run(1.0, 0.0, -0.6);
  EXPECT_LT(rig.body.pose().yaw_rad, -0.3);
  EXPECT_NEAR(rig.last.omega_radps, -0.6, 0.06);
}

TEST(AgilexBase, TheEstopStopsItAndReleasingItLetsItDriveAgain) {
  Rig rig(BaseProtocol::kAgilexV2);
  rig.run(2.0, 0.5);
  rig.body.controller().set_fault(true);  // the e-stop is pressed
  rig.run(0.1, 0.5);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kEstop);
  rig.run(1.0, 0.5);
  EXPECT_NEAR(rig.body.speed_mps(), 0.0, 1e-9);
  rig.body.controller().set_fault(false);
  rig.run(2.0, 0.5);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kNone);
  EXPECT_NEAR(rig.body.speed_mps(), 0.5, 1e-3);
}

TEST(AgilexBase, ItsCommandTimeoutStopsItWhenTheHostFallsSilent) {
  Rig rig(BaseProtocol::kAgilexV2);
  rig.run(2.0, 0.5);
  rig.drive_on = false;
  rig.run(1.0, 0.5);
  EXPECT_NEAR(rig.body.speed_mps(), 0.0, 1e-9);
  for (int k = 0; k < 20; ++k)
    rig.step(0.5, 0.0, false);
  rig.drive_on = true;
  rig.step(0.5, 0.0, false);
  EXPECT_EQ(rig.health().fault, msg::BaseFault::kBaseSilent);
}

TEST(AgilexBase, ReportsTheBasesOwnStatesAndFaultBits) {
  // The base's system state frames as the manual lays them out, straight onto the bus.
  scripted::ManualClock clock = start_clock();
  hal::sim::SimCanLink link(clock);
  AgilexBase base(link.board(), {}, {});
  const auto state = [&](std::uint8_t vehicle, std::uint8_t mode, std::uint8_t fault) {
    agilex::SystemState s{vehicle, mode, 240, fault, 0};
    (void)link.motor().send(agilex::encode(s), clock.now());
    WheelOdometrySample ignored;
    (void)base.poll(ignored);
    (void)base.stop(clock.now());
    return base.health();
  };
  EXPECT_EQ(state(agilex::kVehicleNormal, agilex::kControlModeCan, 0).fault, msg::BaseFault::kNone);
  EXPECT_EQ(
      state(agilex::kVehicleNormal, agilex::kControlModeCan, agilex::kFaultBatteryWarning).fault,
      msg::BaseFault::kNone);  // a warning only
  EXPECT_EQ(state(agilex::kVehicleNormal, agilex::kControlModeCan, agilex::kFaultBatteryLow).fault,
            msg::BaseFault::kLowBattery);
  const DriveHealth h = state(agilex::kVehicleException, agilex::kControlModeCan, 0x04);
  EXPECT_EQ(h.fault, msg::BaseFault::kMotorError);
  EXPECT_EQ(h.code, 0x04u);
  clock.advance(3s);  // past start-up: the RC transmitter holds it
  EXPECT_EQ(state(agilex::kVehicleNormal, agilex::kControlModeRc, 0).fault,
            msg::BaseFault::kNotReady);
}

namespace {
// A bus whose controller went bus-off.
class BusOff final : public CanBus {
 public:
  Status send(const CanFrame&, TimePoint) override { return {Errc::kUnavailable, "bus-off"}; }
  bool receive(CanFrame&) override { return false; }
  CanBusStats stats() const override {
    CanBusStats s;
    s.bus_off = true;
    return s;
  }
};
}  // namespace

TEST(CanBase, BusOffIsAFaultOfEveryProtocol) {
  for (const BaseProtocol p :
       {BaseProtocol::kColag, BaseProtocol::kOdrive, BaseProtocol::kAgilexV2}) {
    BusOff bus;
    BaseConfig cfg;
    cfg.protocol = p;
    CanBase base(bus, cfg, {});
    EXPECT_FALSE(base.drive().stop(TimePoint{1s}));
    EXPECT_EQ(base.drive().health().fault, msg::BaseFault::kBusOff) << to_string(p);
  }
}

TEST(CanBase, FiltersPassExactlyTheBasesFeedback) {
  BaseConfig cfg;
  cfg.protocol = BaseProtocol::kOdrive;
  cfg.odrive.left.node = 3;
  cfg.odrive.right.node = 4;
  const IdFilters f = base_filters(cfg);
  ASSERT_EQ(f.size(), 2u);
  const auto passes = [&](std::uint32_t id) {
    for (const IdFilter& x : f)
      if ((id & x.mask) == (x.id & x.mask)) return true;
    return false;
  };
  EXPECT_TRUE(passes(odrive::can_id(3, odrive::Command::kHeartbeat)));
  EXPECT_TRUE(passes(odrive::can_id(4, odrive::Command::kEncoderEstimates)));
  EXPECT_FALSE(passes(odrive::can_id(5, odrive::Command::kHeartbeat)));
  cfg.protocol = BaseProtocol::kAgilexV2;
  for (const IdFilter& x : base_filters(cfg))
    EXPECT_TRUE(x.id == agilex::kSystemStateId || x.id == agilex::kOdometryId);
}

TEST(CanBase, DriversAllocateNothingWhileDriving) {
  for (const BaseProtocol p :
       {BaseProtocol::kColag, BaseProtocol::kOdrive, BaseProtocol::kAgilexV2}) {
    Rig rig(p);
    rig.run(1.0, 0.4);  // started: closed loop / CAN mode, odometry flowing
    std::uint64_t allocations = 0;
    {
      test::AllocationCounter counter;
      rig.run(2.0, 0.3, 0.2);
      allocations = counter.count();
    }
    EXPECT_EQ(allocations, 0u) << to_string(p);
    EXPECT_GT(rig.samples, 100) << to_string(p);
  }
}
