// The UGV navigation task in closed loop with a small simulated world written here: true
// differential-drive motion from the Drive commands, noisy wheel odometry, a UAV hovering
// overhead that publishes its odometry and relative poses, and map patches.
#include <gtest/gtest.h>

#include <memory>
#include <optional>

#include "allocation_counter.hpp"
#include "colag/common/random.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/platform/lockstep_executor.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/uav/clock_server.hpp"
#include "colag/ugv/ugv_nav_task.hpp"
#include "colag/ugv/waiting.hpp"
#include "map_fixtures.hpp"

using namespace colag;
using namespace colag::ugv;
using namespace std::chrono_literals;

namespace {

class MiniWorld final : public platform::Task {
 public:
  MiniWorld(platform::Transport& bus, hal::scripted::ScriptedWheelOdometry& odo,
            hal::scripted::RecordingDrive& drive, const Pose2& start, const Vec3& uav)
      : truth(start), bus_(bus), odo_(odo), drive_(drive), uav_(uav) {}
  const char* name() const override { return "world"; }
  Status init(TimePoint) override {
    if (Status s = second_clock_.attach(bus_, 1); !s) return s;
    return clock_.attach(bus_, 0);
  }
  void move_uav(const Vec3& to) { uav_ = to; }
  void step(TimePoint now) override {
    clock_.step(now);  // the UAV answers the UGV's clock requests
    // A second UAV answers too, its clock 5 s ahead: fleet time is UAV 0's, its replies unused.
    if (second_uav) second_clock_.step(now + 5s);
    const double dt = 0.02;
    if (odometry_on) {
      const auto& cmd = drive_.last();
      truth.p += cmd.v_mps * dt * Vec2(std::cos(truth.yaw_rad), std::sin(truth.yaw_rad));
      truth.yaw_rad = wrap_angle(truth.yaw_rad + cmd.omega_radps * dt);
      travelled += std::abs(cmd.v_mps) * dt;
      (void)odo_.push(
          {now, cmd.v_mps + rng_.gaussian(0, 0.0336), cmd.omega_radps + rng_.gaussian(0, 0.0292)});
    }
    if (++ticks_ % 2 == 0) {  // 25 Hz
      publish_uav(now, 0, uav_, flight);
      if (second_uav) publish_uav(now, 1, *second_uav, second_flight);
    }
  }
  void publish_uav(TimePoint now, RobotId id, const Vec3& at, msg::UavFlight says) {
    msg::UavOdometry od;
    od.stamp = now;
    od.uav_id = id;
    od.position_m[0] = at.x();
    od.position_m[1] = at.y();
    od.position_m[2] = at.z();
    od.flight = says;
    (void)bus_.publish(od);
    if (!rpe_on || (truth.p - at.head<2>()).norm() > 5.0) return;
    msg::RelativePose rpe;
    rpe.stamp = now;
    rpe.uav_id = id;
    rpe.ugv_id = 0;
    rpe.position_m[0] = truth.p.x() - at.x() + rng_.gaussian(0, 0.2) + next_rpe_error.x();
    rpe.position_m[1] = truth.p.y() - at.y() + rng_.gaussian(0, 0.2) + next_rpe_error.y();
    next_rpe_error = Vec2::Zero();
    rpe.position_m[2] = -at.z();
    const Quat q = quat_from_yaw(truth.yaw_rad + rng_.gaussian(0, 0.05));
    rpe.orientation_wxyz[0] = q.w();
    rpe.orientation_wxyz[3] = q.z();
    rpe.covariance[0] = rpe.covariance[5] = rpe.covariance[10] = 0.04;
    rpe.covariance[15] = 0.0025;
    (void)bus_.publish(rpe);
  }

  bool odometry_on = true;
  bool rpe_on = true;
  msg::UavFlight flight = msg::UavFlight::kInControl;  // what the UAV says of its flight
  std::optional<Vec3> second_uav;                      // a second UAV (id 1) flies here
  msg::UavFlight second_flight = msg::UavFlight::kInControl;
  Vec2 next_rpe_error = Vec2::Zero();  // an outlier: added to the next relative pose only
  double travelled = 0.0;
  Pose2 truth;

 private:
  platform::Transport& bus_;
  hal::scripted::ScriptedWheelOdometry& odo_;
  hal::scripted::RecordingDrive& drive_;
  Vec3 uav_;
  Rng rng_{17};
  int ticks_ = 0;
  uav::ClockServer clock_, second_clock_;
};

// Records the support messages the UGV sends.
class SupportLog final : public platform::SampleSink {
 public:
  void on_sample(msg::Topic, const void* s, TimePoint) override {
    const auto& ci = *static_cast<const msg::CollisionInfo*>(s);
    (ci.cancel ? cancels : requests)++;
    last = ci;
  }
  int requests = 0, cancels = 0;
  msg::CollisionInfo last;
};

// Keeps the last status the UGV sent.
class StatusLog final : public platform::SampleSink {
 public:
  void on_sample(msg::Topic, const void* s, TimePoint) override {
    last = *static_cast<const msg::UgvStatus*>(s);
  }
  msg::UgvStatus last;
};

// What the real-time executor does when the planning loop overruns: report it every step.
class OverrunReporter final : public platform::Task {
 public:
  explicit OverrunReporter(platform::Task& loop) : loop_(loop) {}
  const char* name() const override { return "overruns"; }
  void step(TimePoint) override { loop_.on_overrun(std::chrono::milliseconds(30)); }

 private:
  platform::Task& loop_;
};

struct Rig {
  explicit Rig(const Vec2& goal, const Vec3& uav = Vec3(2, 0, 2), bool report_overruns = false,
               bool start_confirmed = true) {
    config.id = 0;
    config.goal = goal;
    if (!start_confirmed) config.ekf.start_window_s = 0.0;  // the first relative pose starts it
    bus = std::make_unique<platform::LoopbackTransport>(1);
    world = std::make_unique<MiniWorld>(*bus, odo, drive, Pose2{Vec2(0, 0), 0.0}, uav);
    ugv = std::make_unique<UgvNavTask>(config, *bus, odo, drive);
    EXPECT_TRUE(bus->subscribe(msg::topic_of<msg::CollisionInfo>, kAnyRobot, support));
    pump = std::make_unique<platform::TransportPump>(*bus);
    EXPECT_TRUE(ex.add({pump.get(), 10ms, 1ms}));
    EXPECT_TRUE(ex.add({world.get(), 20ms, 1ms}));
    EXPECT_TRUE(ex.add(ugv->rows()));  // the UGV's own schedule table
    if (report_overruns) {
      reporter = std::make_unique<OverrunReporter>(ugv->planning_loop());
      EXPECT_TRUE(ex.add({reporter.get(), 100ms, 1ms}));
    }
    EXPECT_TRUE(ex.init());
  }
  void publish_map(double x0, double y0, double x1, double y1) {
    // The UAV's patches, built by filling a scratch store and re-encoding through the codec.
    PatchCells cells;
    const auto& g = kWorldGrid2d;
    for (double by = y0; by < y1 - 1e-9; by += 6.4) {
      for (double bx = x0; bx < x1 - 1e-9; bx += 6.4) {
        const CellIndex c0 = g.cell_of(Vec2(bx + 1e-6, by + 1e-6));
        cells.width = static_cast<int>(std::lround(std::min(6.4, x1 - bx) / 0.1));
        cells.height = static_cast<int>(std::lround(std::min(6.4, y1 - by) / 0.1));
        cells.cells.fill(CellState::kFree);
        msg::MapPatch patch;
        ASSERT_TRUE(encode_patch(cells, patch));
        patch.stamp = ex.now();
        patch.ugv_id = 0;
        patch.resolution_m = 0.1;
        const Vec2 corner = g.center_of(c0) - Vec2(0.05, 0.05);
        patch.origin_x_m = corner.x();
        patch.origin_y_m = corner.y();
        ASSERT_TRUE(bus->publish(patch));
      }
    }
  }
  // The UAV's list of the UGVs near this one: UGV 1 alone, heard just now.
  void relay_other(msg::UgvMode mode, const Vec2& p, float variance) {
    msg::NearbyUgvs m;
    m.stamp = ex.now();
    m.ugv_id = 0;
    m.radius_m = 12.0;
    m.ugvs.count = 1;
    msg::NearbyUgv& s = m.ugvs[0];
    s.stamp = ex.now();
    s.ugv_id = 1;
    s.mode = mode;
    s.position_m[0] = static_cast<float>(p.x());
    s.position_m[1] = static_cast<float>(p.y());
    s.covariance_xy[0] = s.covariance_xy[2] = variance;
    ASSERT_TRUE(bus->publish(m));
  }
  bool run_until(const std::function<bool()>& done, Duration limit) {
    const TimePoint end = ex.now() + limit;
    while (ex.now() < end) {
      ex.run_until(ex.now() + 100ms);
      if (done()) return true;
    }
    return false;
  }

  UgvNavConfig config;
  hal::scripted::ScriptedWheelOdometry odo;
  hal::scripted::RecordingDrive drive;
  SupportLog support;
  std::unique_ptr<platform::LoopbackTransport> bus;
  std::unique_ptr<MiniWorld> world;
  std::unique_ptr<UgvNavTask> ugv;
  std::unique_ptr<platform::TransportPump> pump;
  std::unique_ptr<OverrunReporter> reporter;
  platform::LockstepExecutor ex;
};

}  // namespace

TEST(UgvNavTask, DrivesToTheGoalThroughAKnownFreeMap) {
  Rig rig(Vec2(4.0, 2.0));
  rig.publish_map(-3.2, -3.2, 9.6, 6.4);
  rig.ex.run_until(TimePoint{200ms});
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);  // initialised by the first two RPEs
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 40s))
      << "mode " << static_cast<int>(rig.ugv->mode());
  EXPECT_LT((rig.world->truth.p - Vec2(4.0, 2.0)).norm(), 0.35);
  EXPECT_LT(rig.world->travelled, 4.47 * 1.2);
  EXPECT_EQ(rig.drive.last().v_mps, 0.0);
  EXPECT_EQ(rig.support.requests, 0);
  // Standing still is waiting, whatever the reason: only at start-up here.
  EXPECT_LE(rig.ugv->waiting_time_s(), 0.3);  // fleet time, then the first relative pose
  // Gaussian tails beyond the 99.9 % gate are dropped as outliers (a few in ~250 updates);
  // nothing else may be rejected.
  const UgvHealth& h = rig.ugv->health();
  EXPECT_LE(h.rpe_outliers, 3u);
  EXPECT_EQ(h.rejected_inputs() - h.rpe_outliers, 0u);
  EXPECT_GT(rig.ugv->estimator().counters().updates, 150u);
}

// A goal sent at run time (the ROS 2 goal_pose): refused with a reason when it cannot be
// driven to, otherwise driven to, even after the UGV had arrived at its first goal.
TEST(UgvNavTask, ANewGoalAtRunTimeIsValidatedThenDrivenTo) {
  Rig rig(Vec2(2.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 6.4);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 30s));
  EXPECT_EQ(rig.ugv->request_goal(Vec2(std::nan(""), 0.0)), GoalResult::kNotFinite);
  EXPECT_EQ(rig.ugv->request_goal(Vec2(20000.0, 0.0)), GoalResult::kOutsideMap);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kArrived);  // refusals change nothing
  EXPECT_EQ(rig.ugv->goal(), Vec2(2.0, 0.0));
  ASSERT_EQ(rig.ugv->request_goal(Vec2(4.0, 3.0)), GoalResult::kAccepted);
  rig.ex.run_until(rig.ex.now() + 300ms);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 30s))
      << "mode " << static_cast<int>(rig.ugv->mode());
  EXPECT_LT((rig.world->truth.p - Vec2(4.0, 3.0)).norm(), 0.35);
  EXPECT_EQ(rig.ugv->last_status().goal_m[0], 4.0);
}

TEST(UgvNavTask, TheOperatorPausesResumesAbortsAndSendsItBackToItsStart) {
  Rig rig(Vec2(4.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 6.4);
  auto command = [&](UgvCommand c) {
    return rig.ugv->request_command(static_cast<std::uint8_t>(c));
  };
  auto operator_s = [&] {
    return to_seconds(rig.ugv->waiting_parts()[static_cast<std::size_t>(WaitPart::kOperator)]);
  };
  auto stands = [&](const char* what) {   // for 2 s, in the mode `what`
    rig.ex.run_until(rig.ex.now() + 1s);  // braking
    const Vec2 held = rig.world->truth.p;
    const double before = operator_s();
    rig.ex.run_until(rig.ex.now() + 2s);
    EXPECT_LT((rig.world->truth.p - held).norm(), 0.02) << what;
    EXPECT_NEAR(operator_s() - before, 2.0, 0.05) << what;  // its waiting says why
  };
  EXPECT_EQ(command(UgvCommand::kReturnToStart), CommandResult::kNoStart);  // not localised yet
  ASSERT_TRUE(rig.run_until([&] { return rig.world->truth.p.x() > 1.0; }, 20s));
  EXPECT_EQ(command(UgvCommand::kResume), CommandResult::kNotPaused);
  EXPECT_EQ(rig.ugv->request_command(0), CommandResult::kUnknown);
  EXPECT_EQ(rig.ugv->request_command(77), CommandResult::kUnknown);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);  // refusals change nothing

  ASSERT_EQ(command(UgvCommand::kPause), CommandResult::kAccepted);
  stands("paused");
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kPaused);
  EXPECT_EQ(rig.ugv->last_status().mode, msg::UgvMode::kPaused);
  ASSERT_EQ(command(UgvCommand::kResume), CommandResult::kAccepted);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 30s));
  EXPECT_LT((rig.world->truth.p - Vec2(4.0, 0.0)).norm(), 0.35);

  // Aborted on the way to another goal: it stands until it is given somewhere to go.
  ASSERT_EQ(rig.ugv->request_goal(Vec2(4.0, 3.0)), GoalResult::kAccepted);
  ASSERT_TRUE(rig.run_until([&] { return rig.world->truth.p.y() > 1.0; }, 20s));
  ASSERT_EQ(command(UgvCommand::kAbort), CommandResult::kAccepted);
  stands("aborted");
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kAborted);
  EXPECT_TRUE(rig.ugv->trajectory().empty());
  EXPECT_EQ(command(UgvCommand::kResume), CommandResult::kNotPaused);  // an abort is not a pause

  // Back to where it was first localised (near its true start, the origin).
  ASSERT_EQ(command(UgvCommand::kReturnToStart), CommandResult::kAccepted);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 40s))
      << "mode " << static_cast<int>(rig.ugv->mode());
  EXPECT_LT(rig.world->truth.p.norm(), 0.5);
}

TEST(UgvNavTask, StopsBeforeTheUnknownAsksForSupportAndGoesOnOnceItIsMapped) {
  Rig rig(Vec2(6.0, 0.0));
  rig.publish_map(-3.2, -3.2, 2.5, 3.2);  // known free up to x = 2.5, unknown beyond
  const bool stopped =
      rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kWaitingForSupport; }, 20s);
  ASSERT_TRUE(stopped) << "mode " << static_cast<int>(rig.ugv->mode()) << " at x "
                       << rig.world->truth.p.x() << " predicted "
                       << static_cast<int>(rig.ugv->prediction().kind) << " t "
                       << rig.ugv->prediction().time_s << " health rpe "
                       << rig.ugv->health().rpe_rejected << "/" << rig.ugv->health().rpe_unmatched
                       << "/" << rig.ugv->health().rpe_outliers;
  rig.ex.run_until(rig.ex.now() + 2s);  // it stays stopped
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kWaitingForSupport);
  EXPECT_LT(rig.world->truth.p.x() + 0.25, 2.5);  // the body never entered the unknown
  EXPECT_GE(rig.support.requests, 1);
  EXPECT_FALSE(rig.support.last.cancel);
  const Vec2 pc(rig.support.last.collision_point_m[0], rig.support.last.collision_point_m[1]);
  const Vec2 ps(rig.support.last.support_point_m[0], rig.support.last.support_point_m[1]);
  EXPECT_NEAR((pc - ps).norm(), 2.0, 1e-9);  // 2 m back along the planned velocity
  EXPECT_LT(ps.x(), pc.x() - 1.9);
  // It may creep a little closer while its estimate firms up standing (the relative poses
  // shrink its covariance; the wheel calibration's share stays): most of the 2 s it waited.
  EXPECT_GT(rig.ugv->waiting_time_s(), 1.0);

  rig.publish_map(2.2, -3.2, 9.6, 3.2);  // the UAV has come and mapped the rest
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 40s));
  EXPECT_GE(rig.support.cancels, 1);
  EXPECT_TRUE(rig.support.last.cancel);
  EXPECT_LT((rig.world->truth.p - Vec2(6.0, 0.0)).norm(), 0.35);
}

TEST(UgvNavTask, ItsStatusSaysWhereItsPathFirstMeetsTheUnknownAndWhen) {
  Rig rig(Vec2(8.0, 0.0));
  StatusLog statuses;
  ASSERT_TRUE(rig.bus->subscribe(msg::topic_of<msg::UgvStatus>, kAnyRobot, statuses));
  rig.publish_map(-3.2, -3.2, 2.5, 3.2);  // known free up to x = 2.5, unknown beyond
  ASSERT_TRUE(rig.run_until([&] { return rig.world->truth.p.x() > 0.3; }, 20s));
  rig.ex.run_until(rig.ex.now() + 200ms);  // a status sent since
  const msg::UgvStatus& s = statuses.last;
  ASSERT_GE(s.scout_in_s, 0.0);
  // The first path point whose CP-Map cell has an unknown cell within the body's radius.
  EXPECT_GT(s.scout_point_m[0], 2.5 - 0.25 - 0.15);
  EXPECT_LT(s.scout_point_m[0], 2.5 + 0.05);
  EXPECT_NEAR(s.scout_point_m[1], 0.0, 0.2);
  // Driving there at no more than v_max, and not slower than the trajectory's own timing
  // (which brakes to rest at the goal 8 m on): a few seconds.
  const double ahead = s.scout_point_m[0] - rig.world->truth.p.x();
  EXPECT_GE(s.scout_in_s, ahead / rig.config.limits.v_max_mps - 0.3);
  EXPECT_LE(s.scout_in_s, ahead / rig.config.limits.v_max_mps + 2.0);

  rig.publish_map(2.2, -3.2, 9.6, 3.2);  // all of its way mapped: nothing to scout
  rig.ex.run_until(rig.ex.now() + 1s);
  EXPECT_LT(statuses.last.scout_in_s, 0.0);
}

TEST(UgvNavTask, PersistentOverrunsShortenThePredictionButItStillStopsBeforeTheUnknown) {
  Rig rig(Vec2(6.0, 0.0), Vec3(2, 0, 2), /*report_overruns=*/true);
  rig.publish_map(-3.2, -3.2, 2.5, 3.2);  // known free up to x = 2.5, unknown beyond
  ASSERT_TRUE(
      rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kWaitingForSupport; }, 20s));
  rig.ex.run_until(rig.ex.now() + 2s);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kWaitingForSupport);
  EXPECT_LT(rig.world->truth.p.x() + 0.25, 2.5);  // the body never entered the unknown
  EXPECT_EQ(rig.ugv->health().degradation, OverrunGovernor::kMaxLevel);
  EXPECT_GT(rig.ugv->health().overruns, 30u);
  EXPECT_GE(rig.support.requests, 1);  // later than with the full look-ahead, but asked
}

// 7 m without a relative pose: its estimate says "at the goal" but 3 sigma is well over 0.3 m.
// It must not call that arrived: it stands and asks the UAV to come to the goal, and arrives
// once a relative pose there confirms it (or takes it the rest of the way).
TEST(UgvNavTask, AtItsGoalByAnUncertainEstimateItAsksForAFixBeforeArriving) {
  Rig rig(Vec2(7.0, 0.0));
  rig.publish_map(-3.2, -6.4, 9.6, 6.4);
  rig.ex.run_until(TimePoint{1s});
  ASSERT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);
  rig.world->rpe_on = false;
  ASSERT_TRUE(rig.run_until(
      [&] {
        return rig.ugv->mode() == msg::UgvMode::kWaitingForSupport &&
               (rig.ugv->estimator().pose().p - Vec2(7.0, 0.0)).norm() < 0.2;
      },
      30s));
  rig.ex.run_until(rig.ex.now() + 2s);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kWaitingForSupport);
  ASSERT_GE(rig.support.requests, 1);
  EXPECT_FALSE(rig.support.last.cancel);
  EXPECT_NEAR(rig.support.last.collision_point_m[0], 7.0, 1e-9);  // "come to my goal"
  rig.world->move_uav(Vec3(7.0, 0.0, 2.0));
  rig.world->rpe_on = true;
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 20s));
  EXPECT_LT((rig.world->truth.p - Vec2(7.0, 0.0)).norm(), 0.35);
}

// Held by another UGV parked in its way, its own estimate (no fix for a while) too uncertain to
// pass at the distance its plan keeps: after robot_fix_after_s it asks the UAV for a fix where
// it stands (the other never moves away), and drives on once fixed.
TEST(UgvNavTask, HeldByAParkedUgvItAsksForAFixWhereItStands) {
  Rig rig(Vec2(8.0, 0.0));
  rig.publish_map(-3.2, -6.4, 9.6, 6.4);
  float parked_variance = 0.09F;  // its 3 sigma 0.9 m (the UAV has not seen it for a while)
  const auto parked = [&] {       // on the straight way to the goal
    rig.relay_other(msg::UgvMode::kArrived, Vec2(4.0, 0.0), parked_variance);
  };
  const auto run_for = [&](Duration d, const std::function<bool()>& done) {
    const TimePoint end = rig.ex.now() + d;
    for (int i = 0; rig.ex.now() < end; ++i) {
      if (i % 5 == 0) parked();
      rig.ex.run_until(rig.ex.now() + 100ms);
      if (done()) return true;
    }
    return false;
  };
  parked();
  rig.ex.run_until(TimePoint{1s});
  rig.world->rpe_on = false;
  ASSERT_TRUE(run_for(30s, [&] { return rig.ugv->mode() == msg::UgvMode::kWaitingForRobot; }));
  const TimePoint held = rig.ex.now();
  const auto asked_here = [&] {
    const Vec2 here = rig.ugv->estimator().pose().p;
    return rig.support.requests > 0 && !rig.support.last.cancel &&
           std::abs(rig.support.last.support_point_m[0] - here.x()) < 0.05 &&
           std::abs(rig.support.last.support_point_m[1] - here.y()) < 0.05;
  };
  ASSERT_TRUE(run_for(15s, asked_here));
  EXPECT_GE(rig.ex.now() - held, 9s);  // robot_fix_after_s: 10 s (the first stop came earlier)
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kWaitingForRobot);
  const Vec2 here = rig.ugv->estimator().pose().p;
  rig.world->move_uav(Vec3(here.x(), here.y(), 2.0));  // the UAV comes: it sees both of them
  rig.world->rpe_on = true;
  parked_variance = 0.0025F;
  EXPECT_TRUE(run_for(40s, [&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }));
}

TEST(UgvNavTask, WheelOdometryLossStopsTheRobotAndReportsAFault) {
  Rig rig(Vec2(6.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  rig.ex.run_until(TimePoint{3s});
  ASSERT_GT(rig.drive.last().v_mps, 0.1);
  rig.world->odometry_on = false;
  rig.ex.run_until(rig.ex.now() + 140ms);  // 100 ms timeout + one control period + slack
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kFault);
  EXPECT_EQ(rig.drive.last().v_mps, 0.0);
  EXPECT_EQ(rig.ugv->health().watchdog_trips, 1u);
  rig.world->odometry_on = true;
  rig.ex.run_until(rig.ex.now() + 200ms);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);
}

TEST(UgvNavTask, ABaseFaultStopsTheRobotAndIsReportedUntilItClears) {
  Rig rig(Vec2(6.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  rig.ex.run_until(TimePoint{3s});
  ASSERT_GT(rig.drive.last().v_mps, 0.1);
  rig.drive.report({msg::BaseFault::kEstop, 0});
  rig.world->odometry_on = false;  // a base in a fault may say nothing more: both at once
  rig.ex.run_until(rig.ex.now() + 300ms);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kFault);
  EXPECT_EQ(rig.drive.last().v_mps, 0.0);
  EXPECT_EQ(rig.ugv->base_fault().fault, msg::BaseFault::kOdometrySilent);
  EXPECT_EQ(rig.ugv->health().base_faults, 1u);  // one fault, however long it lasts
  rig.world->odometry_on = true;
  rig.ex.run_until(rig.ex.now() + 60ms);
  EXPECT_EQ(rig.ugv->base_fault().fault, msg::BaseFault::kEstop);
  rig.drive.report({msg::BaseFault::kMotorError, 0x40});  // another fault: counted again
  rig.ex.run_until(rig.ex.now() + 60ms);
  EXPECT_EQ(rig.ugv->base_fault().code, 0x40u);
  EXPECT_EQ(rig.ugv->health().base_faults, 2u);
  rig.drive.report({});
  rig.ex.run_until(rig.ex.now() + 200ms);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);
  EXPECT_EQ(rig.ugv->base_fault().fault, msg::BaseFault::kNone);
}

TEST(UgvNavTask, AUavWhoseFlightControllerLeftTheMissionStopsItUntilItFliesAgain) {
  Rig rig(Vec2(6.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  rig.ex.run_until(TimePoint{3s});
  ASSERT_GT(rig.drive.last().v_mps, 0.1);
  rig.world->flight = msg::UavFlight::kLost;
  // The UAV's next sample (25 Hz here) + one control period: far inside the 1 s asked for.
  rig.ex.run_until(rig.ex.now() + 100ms);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kUavUnavailable);
  EXPECT_EQ(rig.drive.last().v_mps, 0.0);
  EXPECT_EQ(rig.drive.last().omega_radps, 0.0);
  rig.ex.run_until(rig.ex.now() + 2s);  // it stays stopped while the UAV says so
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kUavUnavailable);
  EXPECT_EQ(rig.drive.last().v_mps, 0.0);
  EXPECT_EQ(rig.ugv->health().uav_unavailable, 1u);
  // A repeated sample (the UAV without fresh odometry) says the flight state and nothing else.
  msg::UavOdometry repeat;
  repeat.stamp = rig.ex.now() - 1s;
  repeat.flight = msg::UavFlight::kLost;
  const auto rejected = rig.ugv->health().uav_odometry_rejected;
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(rig.bus->publish(repeat));
  rig.ex.run_until(rig.ex.now() + 100ms);
  EXPECT_EQ(rig.ugv->health().uav_odometry_rejected, rejected + 1);  // the first: too old
  rig.world->flight = msg::UavFlight::kInControl;
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 40s))
      << "mode " << static_cast<int>(rig.ugv->mode());
}

// Two UAVs 4 m apart both see the UGV: each relative pose is placed by the odometry of the UAV
// that measured it (one history for both would place half of them 4 m off).
TEST(UgvNavTask, WithTwoUavsEachRelativePoseIsPlacedByItsOwnUavsOdometry) {
  Rig rig(Vec2(6.0, 0.0), Vec3(0, 2, 2));
  rig.world->second_uav = Vec3(4, -2, 2);
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 40s))
      << "mode " << static_cast<int>(rig.ugv->mode());
  EXPECT_LT((rig.ugv->estimator().pose().p - rig.world->truth.p).norm(), 0.3);
  EXPECT_LE(rig.ugv->health().rpe_outliers, 2u);
  EXPECT_EQ(rig.ugv->health().rpe_unmatched, 0u);
  // Fleet time is UAV 0's clock; UAV 1's replies (5 s ahead) were not mixed in.
  const platform::UgvFleetClock& clock = rig.ugv->fleet_clock();
  EXPECT_GT(clock.replies_rejected(), 10u);
  EXPECT_LT(std::abs(to_seconds(clock.to_local(rig.ex.now()) - rig.ex.now())), 0.01);
}

// One of two UAVs leaves the mission: the other still flies it, the UGV drives on. Only when
// neither does is no support coming.
TEST(UgvNavTask, OneUavOfTwoLeavingTheMissionDoesNotStopIt) {
  Rig rig(Vec2(6.0, 0.0));
  rig.world->second_uav = Vec3(2, 2, 2);
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  rig.ex.run_until(TimePoint{3s});
  ASSERT_GT(rig.drive.last().v_mps, 0.1);
  rig.world->second_flight = msg::UavFlight::kLost;
  rig.ex.run_until(rig.ex.now() + 500ms);
  EXPECT_NE(rig.ugv->mode(), msg::UgvMode::kUavUnavailable);
  EXPECT_EQ(rig.ugv->health().uav_unavailable, 1u);
  rig.world->flight = msg::UavFlight::kLanding;
  rig.ex.run_until(rig.ex.now() + 200ms);
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kUavUnavailable);
  EXPECT_EQ(rig.drive.last().v_mps, 0.0);
  rig.world->second_flight = msg::UavFlight::kInControl;
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 40s))
      << "mode " << static_cast<int>(rig.ugv->mode());
}

TEST(UgvNavTask, RejectsAndCountsBadMessagesWithoutHarm) {
  Rig rig(Vec2(4.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  rig.ex.run_until(TimePoint{1s});
  msg::RelativePose nan_rpe;
  nan_rpe.stamp = rig.ex.now();
  nan_rpe.position_m[0] = std::numeric_limits<double>::quiet_NaN();
  nan_rpe.covariance[0] = nan_rpe.covariance[5] = nan_rpe.covariance[10] = nan_rpe.covariance[15] =
      0.01;
  ASSERT_TRUE(rig.bus->publish(nan_rpe));
  msg::RelativePose future = nan_rpe;
  future.position_m[0] = 0.0;
  future.stamp = rig.ex.now() + 10s;
  ASSERT_TRUE(rig.bus->publish(future));
  msg::MapPatch garbage;
  garbage.stamp = rig.ex.now();
  garbage.width_cells = 3000;
  ASSERT_TRUE(rig.bus->publish(garbage));
  msg::NearbyUgvs nearby;  // the UAV's list of the UGVs near it, with two bad entries
  nearby.stamp = rig.ex.now();
  nearby.ugv_id = 0;
  nearby.ugvs.count = 2;
  nearby.ugvs[0].ugv_id = 200;
  msg::NearbyUgv& bad_velocity = nearby.ugvs[1];  // right ahead: its velocity would sweep it away
  bad_velocity.ugv_id = 3;
  bad_velocity.position_m[0] = 2.0;
  bad_velocity.velocity_mps = std::numeric_limits<float>::infinity();
  ASSERT_TRUE(rig.bus->publish(nearby));
  rig.ex.run_until(rig.ex.now() + 200ms);
  EXPECT_EQ(rig.ugv->health().rpe_rejected, 2u);
  EXPECT_EQ(rig.ugv->health().patches_rejected, 1u);
  EXPECT_EQ(rig.ugv->health().statuses_rejected, 2u);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 30s));
}

// A camera outlier (1.8 m off, 6 sigma) as the very first relative pose: taken as the start, the
// estimator believed it within its reported 0.2 m; now it waits for two that agree.
TEST(UgvNavTask, AnOutlierCannotStartTheEstimator) {
  for (const bool agreement : {true, false}) {
    Rig rig(Vec2(4.0, 0.0), Vec3(2, 0, 2), false, agreement);
    rig.world->rpe_on = false;  // relative poses are refused until fleet time is known
    ASSERT_TRUE(
        rig.run_until([&] { return rig.ugv->fleet_clock().synchronised(rig.ex.now()); }, 2s));
    rig.world->rpe_on = true;
    rig.world->next_rpe_error = Vec2(1.5, 1.0);
    ASSERT_TRUE(rig.run_until([&] { return rig.ugv->estimator().initialized(); }, 2s));
    const double error = (rig.ugv->estimator().pose().p - rig.world->truth.p).norm();
    if (agreement) {
      EXPECT_LT(error, 0.4);
      EXPECT_EQ(rig.ugv->estimator().counters().unconfirmed, 1U);
    } else {
      EXPECT_GT(error, 1.2);  // what it did: started on the outlier
    }
  }
}

// One UAV odometry sample stamped an hour ahead used to become the history's newest: every
// genuine sample after it was refused as "not increasing", no relative pose found its UAV pose,
// and the UGV never initialised. Now it is refused as from the future, and nothing else is.
TEST(UgvNavTask, AFutureStampedUavOdometrySampleLocksNothingOut) {
  Rig rig(Vec2(4.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 3.2);
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->fleet_clock().synchronised(rig.ex.now()); }, 1s));
  msg::UavOdometry future;
  future.stamp = rig.ex.now() + 1h;
  future.position_m[2] = 2.0;
  ASSERT_TRUE(rig.bus->publish(future));
  rig.ex.run_until(TimePoint{2s});
  const UgvHealth& h = rig.ugv->health();
  EXPECT_EQ(h.stamps.from_future, 1u);
  EXPECT_EQ(h.uav_odometry_rejected, 1u);
  EXPECT_EQ(h.rpe_unmatched, 0u);
  EXPECT_TRUE(rig.ugv->estimator().initialized());
  ASSERT_TRUE(rig.run_until([&] { return rig.ugv->mode() == msg::UgvMode::kArrived; }, 30s));
}

// Another UGV that falls silent (its firmware died, or every message is lost) is not forgotten
// after 3 s: it stays an obstacle whose disc grows with the time since it was heard, bounded by
// its top speed; heard again, it shrinks back to its reported uncertainty.
TEST(UgvNavTask, ASilentUgvStaysAnObstacleThatGrowsUntilItIsHeardAgain) {
  Rig rig(Vec2(8.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 6.4);
  // The UAV relays UGV 1's status (heard just now), then goes silent.
  const auto other_status = [&] {  // 2 m beside the way to the goal
    rig.relay_other(msg::UgvMode::kDriving, Vec2(5.0, 2.0), 1e-4F);
  };
  other_status();  // heard once, then silent
  ASSERT_TRUE(rig.run_until(
      [&] {
        return rig.ugv->mode() == msg::UgvMode::kWaitingForSupport ||
               rig.ugv->mode() == msg::UgvMode::kNoPath;
      },
      10s));
  rig.ex.run_until(rig.ex.now() + 10s);  // long past the 3 s after which it was forgotten
  EXPECT_NE(rig.ugv->mode(), msg::UgvMode::kDriving);
  EXPECT_NE(rig.ugv->mode(), msg::UgvMode::kArrived);
  EXPECT_LT(rig.world->truth.p.x(), 4.0);  // it never drove past the silent one

  other_status();  // heard again, where it was: the way is clear
  for (int i = 0; i < 300 && rig.ugv->mode() != msg::UgvMode::kArrived; ++i) {
    rig.ex.run_until(rig.ex.now() + 100ms);
    if (i % 5 == 0) other_status();  // and heard from every half second now
  }
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kArrived);
}

// The UAV's lists are complete within their radius: a UGV left out of a newer one is farther
// and is forgotten at once, rather than lingering in the way as a silent one would.
TEST(UgvNavTask, AUgvLeftOutOfTheUavsNewerListIsForgotten) {
  Rig rig(Vec2(8.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 6.4);
  const auto relay = [&](bool with_ugv1) {
    msg::NearbyUgvs m;
    m.stamp = rig.ex.now();
    m.ugv_id = 0;
    m.radius_m = 12.0;
    if (with_ugv1) {
      m.ugvs.count = 1;
      msg::NearbyUgv& s = m.ugvs[0];
      s.stamp = rig.ex.now();
      s.ugv_id = 1;
      s.mode = msg::UgvMode::kWaitingForSupport;
      s.position_m[0] = 8.0;  // standing on its goal
      s.covariance_xy[0] = s.covariance_xy[2] = 1e-4F;
    }
    ASSERT_TRUE(rig.bus->publish(m));
  };
  for (int i = 0; i < 80; ++i) {
    relay(true);
    rig.ex.run_until(rig.ex.now() + 100ms);
  }
  EXPECT_NE(rig.ugv->mode(), msg::UgvMode::kArrived);
  EXPECT_GT((rig.world->truth.p - Vec2(8.0, 0.0)).norm(), 0.6) << "it drove into the other UGV";
  for (int i = 0; i < 300 && rig.ugv->mode() != msg::UgvMode::kArrived; ++i) {
    relay(false);
    rig.ex.run_until(rig.ex.now() + 100ms);
  }
  EXPECT_EQ(rig.ugv->mode(), msg::UgvMode::kArrived);
}

// Every other list is a near one (6 m, uav/nearby_relay.hpp): a UGV missing from it is
// forgotten only where the list would have held it; one farther is kept until a full list
// leaves it out, or for a second without any list holding it.
TEST(UgvNavTask, ANearListForgetsOnlyTheUgvsWithinItsRadius) {
  Rig rig(Vec2(8.0, 0.0));
  rig.publish_map(-3.2, -3.2, 9.6, 12.8);
  const auto relay = [&](double radius_m, std::initializer_list<std::pair<RobotId, Vec2>> ugvs) {
    msg::NearbyUgvs m;
    m.stamp = rig.ex.now();
    m.ugv_id = 0;
    m.radius_m = radius_m;
    for (const auto& [id, at] : ugvs) {
      msg::NearbyUgv& s = m.ugvs[m.ugvs.count++];
      s.stamp = rig.ex.now();
      s.ugv_id = id;
      s.mode = msg::UgvMode::kDriving;
      s.position_m[0] = static_cast<float>(at.x());
      s.position_m[1] = static_cast<float>(at.y());
      s.covariance_xy[0] = s.covariance_xy[2] = 1e-4F;
    }
    ASSERT_TRUE(rig.bus->publish(m));
    rig.ex.run_until(rig.ex.now() + 100ms);
  };
  const Vec2 far(0.0, 9.0), near(0.0, 3.0);
  relay(12.0, {{2, near}, {1, far}});
  EXPECT_TRUE(rig.ugv->knows_ugv(1));
  EXPECT_TRUE(rig.ugv->knows_ugv(2));
  relay(6.0, {{2, near}});
  EXPECT_TRUE(rig.ugv->knows_ugv(1)) << "a near list says nothing of a UGV 9 m away";
  relay(6.0, {});
  EXPECT_FALSE(rig.ugv->knows_ugv(2)) << "3 m away and not in a 6 m list: gone";
  EXPECT_TRUE(rig.ugv->knows_ugv(1));
  relay(12.0, {});
  EXPECT_FALSE(rig.ugv->knows_ugv(1)) << "not in a full list";

  relay(12.0, {{1, far}});
  for (int i = 0; i < 8; ++i)
    relay(6.0, {});
  EXPECT_TRUE(rig.ugv->knows_ugv(1));
  for (int i = 0; i < 3; ++i)
    relay(6.0, {});
  EXPECT_FALSE(rig.ugv->knows_ugv(1)) << "no list held it for over a second";
}

TEST(UgvNavTask, StepsAllocateNothingInSteadyState) {
  Rig rig(Vec2(0.0, 15.0), Vec3(0, 5, 2));
  rig.publish_map(-6.4, -3.2, 6.4, 19.2);
  rig.ex.run_until(TimePoint{2s});  // warm-up: initialised, planned, driving
  ASSERT_EQ(rig.ugv->mode(), msg::UgvMode::kDriving);
  const auto plans_before = rig.ugv->health().plans;
  {
    test::AllocationCounter counter;
    for (int i = 0; i < 1000; ++i)
      rig.ex.step();  // 1000 executor instants ~ 10 s
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_GE(rig.ugv->health().plans - plans_before, 8u);  // replanning was part of it
  EXPECT_GT(rig.world->travelled, 3.0);
}
