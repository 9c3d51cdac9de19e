// The UAV supervisor task with scripted devices: a point-mass UAV that follows the setpoints,
// the mock LiDAR over a box world, and UGVs played by the test through the transport.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "allocation_counter.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/platform/lockstep_executor.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/world/lidar_simulator.hpp"
#include "colag/uav/rpe_relay.hpp"
#include "colag/uav/uav_supervisor_task.hpp"

using namespace colag;
using namespace colag::uav;
using namespace std::chrono_literals;

namespace {

// The UAV body and its sensors: follows velocity setpoints (acceleration-limited), scans the
// world at 10 Hz, sees UGVs within 5 m.
class Sky final : public platform::Task {
 public:
  Sky(hal::scripted::ScriptedOdometrySource& odom, hal::scripted::ScriptedLidar& lidar,
      hal::scripted::ScriptedRelativePoseSensor& camera,
      hal::scripted::RecordingFlightController& fc, const sim::BoxWorld& world)
      : odom_(odom),
        lidar_(lidar),
        camera_(camera),
        fc_(fc),
        world_(world),
        sim_(std::make_unique<sim::LidarSimulator>()) {}
  const char* name() const override { return "sky"; }
  void step(TimePoint now) override {
    const double dt = 0.02;
    if (fc_.count() > 0) {
      Vec3 dv = fc_.last().velocity_mps - v;
      if (dv.norm() > 1.0 * dt) dv *= 1.0 * dt / dv.norm();
      v += dv;
    }
    p += v * dt;
    travelled += v.norm() * dt;
    hal::UavState s;
    s.stamp = now;
    s.pose = {p, Quat::Identity()};
    s.velocity_mps = v;
    if (odometry_on) (void)odom_.push(s);
    if (++ticks_ % 5 == 0) {  // 10 Hz
      std::span<const hal::LidarPoint> pts, misses;
      sim_->scan(world_, s.pose, pts, misses);
      // A real driver's scan (returns only) when asked; the misses listed otherwise.
      (void)lidar_.set_scan(now, 8.0F, pts,
                            returns_only ? std::span<const hal::LidarPoint>{} : misses);
      hal::scripted::ScriptedRelativePoseSensor::Frame frame;
      for (std::size_t i = 0; i < ugvs.size(); ++i) {
        const auto id = static_cast<RobotId>(i);
        const Vec3 rel = Vec3(ugvs[i].x(), ugvs[i].y(), 0.0) - p;
        if (rel.head<2>().norm() > 5.0) continue;
        hal::RelativePoseDetection d;
        d.stamp = now;
        d.ugv_id = id;
        d.ugv_in_uav = {rel, Quat::Identity()};
        d.covariance = Eigen::Vector4d(0.04, 0.04, 0.04, 0.0025).asDiagonal();
        (void)frame.push_back(d);
      }
      (void)camera_.push_frame(frame);
    }
  }
  Vec3 p = Vec3(0, 0, 1);
  Vec3 v = Vec3::Zero();
  double travelled = 0.0;
  std::vector<Vec2> ugvs;  // where the UGVs are (for the camera)
  bool returns_only = false;
  bool odometry_on = true;

 private:
  hal::scripted::ScriptedOdometrySource& odom_;
  hal::scripted::ScriptedLidar& lidar_;
  hal::scripted::ScriptedRelativePoseSensor& camera_;
  hal::scripted::RecordingFlightController& fc_;
  const sim::BoxWorld& world_;
  std::unique_ptr<sim::LidarSimulator> sim_;
  int ticks_ = 0;
};

template <class Msg>
class Collect final : public platform::SampleSink {
 public:
  Collect() { got.reserve(4096); }  // the allocation test counts the test's own sinks too
  void on_sample(msg::Topic, const void* s, TimePoint) override {
    got.push_back(*static_cast<const Msg*>(s));
  }
  std::vector<Msg> got;
};

struct Rig {
  // `fork_join` (optional): the mapper splits each scan over its workers, as on a board.
  explicit Rig(ForkJoin* fork_join = nullptr, const UavSupervisorConfig& config = {}) {
    sim::MapGenConfig cfg;
    cfg.boxes = 40;
    cfg.seed = 3;
    world = sim::generate_box_world(cfg).value();
    bus = std::make_unique<platform::LoopbackTransport>(1);
    lidar = std::make_unique<hal::scripted::ScriptedLidar>();
    sky = std::make_unique<Sky>(odom, *lidar, camera, fc, world);
    uav = std::make_unique<UavSupervisorTask>(config, *bus, odom, *lidar, camera, fc, fork_join);
    pump = std::make_unique<platform::TransportPump>(*bus);
    EXPECT_TRUE(bus->subscribe(msg::topic_of<msg::MapPatch>, kAnyRobot, patches));
    EXPECT_TRUE(bus->subscribe(msg::topic_of<msg::SupportPlan>, kAnyRobot, plans));
    EXPECT_TRUE(bus->subscribe(msg::topic_of<msg::RelativePose>, kAnyRobot, rpes));
    EXPECT_TRUE(ex.add({pump.get(), 10ms, 1ms}));
    EXPECT_TRUE(ex.add({sky.get(), 20ms, 5ms}));
    EXPECT_TRUE(ex.add(uav->rows()));  // the UAV's own schedule table
    EXPECT_TRUE(ex.init());
  }
  // `scout_in_s` >= 0: its path meets unknown ground at `scout` in that many seconds.
  void status(RobotId id, Vec2 p, msg::UgvMode mode = msg::UgvMode::kDriving,
              Vec2 scout = Vec2::Zero(), double scout_in_s = -1.0) {
    msg::UgvStatus s;
    s.stamp = ex.now();
    s.ugv_id = id;
    s.mode = mode;
    s.position_m[0] = p.x();
    s.position_m[1] = p.y();
    s.yaw_rad = -M_PI / 2;
    s.scout_point_m[0] = scout.x();
    s.scout_point_m[1] = scout.y();
    s.scout_in_s = scout_in_s;
    ASSERT_TRUE(bus->publish(s));
  }
  // `collision`: its collision point (default: 2 m ahead of where the tests place the UGV).
  void request(RobotId id, Vec2 support, double t_pc, bool cancel = false,
               const std::optional<Vec2>& collision = std::nullopt) {
    msg::CollisionInfo ci;
    ci.stamp = ex.now();
    ci.ugv_id = id;
    ci.seq = ++seq;
    ci.cancel = cancel;
    ci.support_point_m[0] = support.x();
    ci.support_point_m[1] = support.y();
    // The tests place each UGV 2 m south of its support point: its collision 2 m ahead of it.
    const Vec2 c = collision.value_or(support - Vec2(0.0, 4.0));
    ci.collision_point_m[0] = c.x();
    ci.collision_point_m[1] = c.y();
    ci.time_to_collision_s = t_pc;
    ASSERT_TRUE(bus->publish(ci));
  }
  double distance_to(const Vec2& q) const { return (sky->p.head<2>() - q).norm(); }

  sim::BoxWorld world;
  hal::scripted::ScriptedOdometrySource odom;
  std::unique_ptr<hal::scripted::ScriptedLidar> lidar;
  hal::scripted::ScriptedRelativePoseSensor camera;
  hal::scripted::RecordingFlightController fc;
  std::unique_ptr<platform::LoopbackTransport> bus;
  std::unique_ptr<Sky> sky;
  std::unique_ptr<UavSupervisorTask> uav;
  std::unique_ptr<platform::TransportPump> pump;
  Collect<msg::MapPatch> patches;
  Collect<msg::SupportPlan> plans;
  Collect<msg::RelativePose> rpes;
  platform::LockstepExecutor ex;
  std::uint32_t seq = 0;
};

}  // namespace

TEST(UavSupervisorTask, FliesTheScheduledOrderHoversUntilCancelledThenMovesOn) {
  Rig rig;
  // UGV 0 needs support soon near (6, 0); UGV 1 later near (-8, 6).
  const Vec2 a(6.0, 0.0), b(-8.0, 6.0);
  rig.sky->ugvs = {Vec2(6, -2), Vec2(-8, 4)};
  rig.status(0, Vec2(6, -2));
  rig.status(1, Vec2(-8, 4));
  rig.request(0, a, 8.0);
  rig.request(1, b, 40.0);
  rig.ex.run_until(rig.ex.now() + 500ms);
  ASSERT_FALSE(rig.plans.got.empty());
  const msg::SupportPlan& plan = rig.plans.got.back();
  ASSERT_EQ(plan.stops.count, 2);
  EXPECT_EQ(plan.stops[0].ugv_id, 0);  // the urgent one first
  EXPECT_EQ(plan.stops[1].ugv_id, 1);
  EXPECT_EQ(rig.uav->mode(), UavMode::kTransit);
  // It gets there and hovers (requests heartbeat every second, as the UGVs do).
  for (int i = 0; i < 10 && rig.distance_to(a) > 1.0; ++i) {
    rig.request(0, a, 8.0 - i);
    rig.request(1, b, 40.0 - i);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(a), 1.0);
  rig.ex.run_until(rig.ex.now() + 300ms);
  EXPECT_EQ(rig.uav->mode(), UavMode::kHover);
  // Seen by the camera on the way: relative poses went out for UGV 0.
  bool saw0 = false;
  for (const auto& r : rig.rpes.got)
    saw0 |= r.ugv_id == 0;
  EXPECT_TRUE(saw0);
  // UGV 0 is fine now: cancel; the UAV goes on to UGV 1.
  rig.request(0, a, 0.0, /*cancel=*/true);
  for (int i = 0; i < 20 && rig.distance_to(b) > 1.0; ++i) {
    rig.request(1, b, 30.0 - i);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(b), 1.0);
  EXPECT_LT(rig.sky->travelled, 1.3 * ((a - Vec2(0, 0)).norm() + (b - a).norm()));
  EXPECT_GT(rig.uav->health().schedules_exact, 0u);
  // The order [0, 1] stood while the UAV flew to UGV 0: each step was warm-started from it.
  EXPECT_GT(rig.uav->health().plan_age_max, 5u);
  EXPECT_EQ(rig.uav->health().requests_rejected, 0u);
}

TEST(UavSupervisorTask, HoverTimeoutGivesOthersATurn) {
  Rig rig;
  const Vec2 a(2.0, 0.0), b(-6.0, 0.0);
  rig.status(0, Vec2(2, -2));
  rig.status(1, Vec2(-6, -2));
  for (int i = 0; i < 30 && rig.uav->health().hover_timeouts == 0; ++i) {  // UGV 0 never cancels
    rig.request(0, a, 3.0);
    rig.request(1, b, 60.0);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_EQ(rig.uav->health().hover_timeouts, 1u);
  for (int i = 0; i < 10; ++i) {
    rig.request(0, a, 3.0);
    rig.request(1, b, 50.0);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  // Circling b: the orbit is a point moving round a 2 m circle that the flight planner chases
  // with a 1.5 m lookahead, so the distance swings between ~1 and ~3.6 m (and differs between
  // x86-64 and aarch64 rounding); what matters is that b is being served.
  EXPECT_LT(rig.distance_to(b), 4.0);
  EXPECT_EQ(rig.uav->mode(), UavMode::kHover);
  // UGV 0's turn comes back after the cooldown (20 s): it is not abandoned.
  for (int i = 0; i < 30 && rig.distance_to(a) > 3.0; ++i) {
    rig.request(0, a, 3.0);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(a), 3.0);
}

TEST(UavSupervisorTask, ScoutsWhereAPathMeetsTheUnknownSoonestAndARequestComesFirst) {
  UavSupervisorConfig config;
  config.scouting = true;
  Rig rig(nullptr, config);
  // UGV 1's path meets unknown ground in 5 s at c, UGV 0's in 20 s at d; nothing requested.
  const Vec2 c(-6.0, -6.0), d(6.0, -6.0), a(6.0, 0.0);
  const auto statuses = [&] {
    rig.status(0, Vec2(6, 2), msg::UgvMode::kDriving, d, 20.0);
    rig.status(1, Vec2(-6, -2), msg::UgvMode::kDriving, c, 5.0);
  };
  for (int i = 0; i < 8 && rig.distance_to(c) > 3.0; ++i) {
    statuses();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(c), 3.0);  // circling c (2 m radius)
  EXPECT_EQ(rig.uav->mode(), UavMode::kScout);
  EXPECT_TRUE(rig.plans.got.empty() || rig.plans.got.back().stops.count == 0);
  // UGV 0 asks for support at a: that comes first, whatever is being scouted.
  rig.request(0, a, 6.0);
  rig.ex.run_until(rig.ex.now() + 200ms);
  EXPECT_EQ(rig.uav->mode(), UavMode::kTransit);
  for (int i = 0; i < 12 && rig.distance_to(a) > 1.0; ++i) {
    statuses();
    rig.request(0, a, 6.0 - i);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(a), 1.0);
  // Served: back to scouting. UGV 1's point never moves (a cell the UAV cannot map): after
  // scout_timeout circling it, the UAV leaves it for UGV 0's.
  rig.request(0, a, 0.0, /*cancel=*/true);
  for (int i = 0; i < 30 && rig.uav->health().scout_timeouts == 0; ++i) {
    statuses();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_EQ(rig.uav->health().scout_timeouts, 1u);
  for (int i = 0; i < 12 && rig.distance_to(d) > 3.0; ++i) {
    statuses();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(d), 3.0);
  EXPECT_GT(rig.uav->health().mode_steps[static_cast<std::size_t>(UavMode::kScout)], 0u);
}

TEST(UavSupervisorTask, WithoutScoutingItLeadsTheUgvsAndNeverScouts) {
  Rig rig;  // scouting off: the paper's idle
  for (int i = 0; i < 6; ++i) {
    rig.status(0, Vec2(6, 2), msg::UgvMode::kDriving, Vec2(6, -6), 20.0);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_EQ(rig.uav->mode(), UavMode::kIdle);
  EXPECT_EQ(rig.uav->health().mode_steps[static_cast<std::size_t>(UavMode::kScout)], 0u);
  EXPECT_LT(rig.distance_to(Vec2(6, 2)), 4.0);   // by the UGV it leads
  EXPECT_GT(rig.distance_to(Vec2(6, -6)), 4.0);  // not at its scouting point
}

TEST(UavSupervisorTask, MapPatchesReachEveryUgvAtItsOwnRate) {
  Rig rig;
  // 16 UGVs around the arena; the UAV flies a slow circle so the map keeps changing.
  for (int round = 0; round < 30; ++round) {
    for (RobotId id = 0; id < 16; ++id)
      rig.status(id, Vec2(-9.0 + 1.2 * id, (id % 2 ? 3.0 : -3.0)));
    rig.request(0, Vec2(4.0 * std::cos(round * 0.2), 4.0 * std::sin(round * 0.2)), 5.0);
    rig.ex.run_until(rig.ex.now() + 100ms);
  }
  std::array<int, 16> per_ugv{};
  std::array<TimePoint, 16> last{};
  for (const auto& p : rig.patches.got) {
    ASSERT_LT(p.ugv_id, 16);
    if (per_ugv[p.ugv_id]++ > 0) {
      EXPECT_GE(p.stamp - last[p.ugv_id], 200ms) << "faster than 5 Hz";
    }
    last[p.ugv_id] = p.stamp;
    EXPECT_LE(p.width_cells, limits::kMaxPatchSideCells);
  }
  for (int id = 0; id < 16; ++id)
    EXPECT_GE(per_ugv[id], 3) << "UGV " << id << " starved";
}

TEST(UavSupervisorTask, PatchesAreHundredsOfTimesSmallerThanTheOriginalFormat) {
  Rig rig;
  for (int i = 0; i < 40; ++i) {
    rig.status(0, Vec2(0.0, -4.0));
    rig.request(0, Vec2(0.0, 8.0 - 0.4 * i), 5.0);  // drag the UAV along a line
    rig.ex.run_until(rig.ex.now() + 100ms);
  }
  ASSERT_FALSE(rig.patches.got.empty());
  // Payload against payload: our encoded cells against the original's int32 address lists of
  // the same 5 x 5 x 1.4 m box (headers excluded on both sides; the closing note gives both).
  std::size_t ours = 0, original = 0;
  constexpr std::size_t kOriginalHeader = 16 + 2 * 4 + 8 + 3 * 8 + 3 * 4 + 6 * 8 + 2 * 4;
  for (const auto& p : rig.patches.got) {
    ours += p.data.count;
    original += original_patch_bytes(rig.uav->mapper(), p, -0.7, 0.7) - kOriginalHeader;
  }
  EXPECT_GE(static_cast<double>(original) / static_cast<double>(ours), 100.0)
      << "ours " << ours << " B, original " << original << " B over " << rig.patches.got.size()
      << " patches";
}

// Counted on every thread: the mapper's work on the pool's worker thread is the task's too.
// Twice: scans that list their misses, and a real driver's (returns only, the misses inferred
// from the LiDAR's pattern).
class UavSupervisorSteps : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(Scans, UavSupervisorSteps, ::testing::Values(false, true),
                         [](const auto& p) { return p.param ? "ReturnsOnly" : "WithMisses"; });

TEST_P(UavSupervisorSteps, AllocateNothingInSteadyState) {
  platform::WorkerPool pool(1);
  UavSupervisorConfig config;
  config.lidar_pattern.beams = 32;  // the simulated VLP-32's (the other fields' defaults)
  Rig rig(&pool, config);
  rig.sky->returns_only = GetParam();
  rig.sky->ugvs = {Vec2(2, 1), Vec2(-3, 2)};
  rig.status(0, Vec2(2, 1));
  rig.status(1, Vec2(-3, 2));
  rig.request(0, Vec2(3, 3), 20.0);
  rig.request(1, Vec2(-4, 4), 30.0);
  rig.ex.run_until(TimePoint{2s});
  {
    test::AllocationCounter counter;
    for (int i = 0; i < 1000; ++i) {
      if (i % 100 == 0) {  // the UGVs' heartbeats, as in a mission
        rig.status(0, Vec2(2, 1));
        rig.status(1, Vec2(-3, 2));
        rig.request(0, Vec2(3, 3), 20.0);
        rig.request(1, Vec2(-4, 4), 30.0);
      }
      rig.ex.step();
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_GT(rig.uav->mapper().counters().scans, 10u);
  EXPECT_EQ(rig.uav->no_return_beams().counters().scans_completed > 0, GetParam());
  EXPECT_GT(rig.uav->health().patches_sent, 0u);
  EXPECT_GT(rig.uav->health().rpe_published, 0u);
}

TEST(RpeRelay, RefusesMalformedDetections) {
  hal::RelativePoseDetection d;
  d.ugv_id = 3;
  d.covariance = Eigen::Vector4d(0.04, 0.04, 0.04, 0.0025).asDiagonal();
  ASSERT_TRUE(to_message(d, 0));
  EXPECT_EQ(to_message(d, 0)->ugv_id, 3);
  hal::RelativePoseDetection bad = d;
  bad.ugv_id = 99;
  EXPECT_FALSE(to_message(bad, 0));
  bad = d;
  bad.ugv_in_uav.p.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(to_message(bad, 0));
  bad = d;
  bad.covariance(3, 3) = 0.0;
  EXPECT_FALSE(to_message(bad, 0));
  bad = d;
  bad.ugv_in_uav.q.coeffs() *= 2.0;
  EXPECT_FALSE(to_message(bad, 0));
}

TEST(UavSupervisorTask, RejectsRequestsWithHostileStampsOrValues) {
  Rig rig;
  rig.ex.run_until(TimePoint{1s});
  msg::CollisionInfo ci;
  ci.ugv_id = 1;
  ci.seq = 1;
  ci.time_to_collision_s = 3.0;
  ci.stamp = TimePoint::min();  // far past: would overflow every "how long ago" computation
  ASSERT_TRUE(rig.bus->publish(ci));
  ci.stamp = rig.ex.now() + 1h;  // from the future
  ASSERT_TRUE(rig.bus->publish(ci));
  ci.stamp = rig.ex.now();
  ci.time_to_collision_s = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(rig.bus->publish(ci));
  ci.time_to_collision_s = 3.0;
  ci.ugv_id = 500;
  ASSERT_TRUE(rig.bus->publish(ci));
  rig.ex.run_until(rig.ex.now() + 500ms);
  EXPECT_EQ(rig.uav->health().requests_rejected, 4u);
  EXPECT_EQ(rig.uav->schedule().order.size(), 0u);
}

TEST(UavSupervisorTask, FliesAsHighAsItsCameraWantsAndItsLidarAllows) {
  const auto altitude = [](double lowest_beam_deg, int beams) {
    UavSupervisorConfig c;
    c.camera_view = {4.0, 60.0, 0.3};  // widest disc of tags from 0.3 + 4 cos 60 = 2.3 m
    c.lidar_pattern = {beams, lowest_beam_deg, 1.2, 1200};
    const Rig rig(nullptr, c);
    return rig.uav->config().flight.altitude_m;
  };
  const double configured = UavSupervisorConfig{}.flight.altitude_m;
  // A -25.2 deg lowest beam leaves a 3.2 m blind disc on the body band from 1.606 m.
  EXPECT_NEAR(altitude(-25.2, 32), 0.1 + 3.2 * std::tan(25.2 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(altitude(-40.0, 32), 2.3, 1e-9);  // a steeper one: where the camera sees most
  EXPECT_EQ(altitude(-25.2, 0), configured);    // a LiDAR not described: as configured
}

// A UGV stopped by the ground right at its front edge (the start of a mission): the usual
// orbit, 2 m round a point 2 m behind it, keeps that ground in the LiDAR's blind disc or behind
// the UGV's body. The UAV circles the UGV itself from outside the blind disc, starting in front.
TEST(UavSupervisorTask, CirclesAUgvAgainstItsOwnEdgeFromOutsideItsBlindDisc) {
  UavSupervisorConfig c;
  c.camera_view = {5.0, 75.0, 0.3};
  c.lidar_pattern = {32, -25.2, 1.2, 1200};
  Rig rig(nullptr, c);
  const double h = rig.uav->config().flight.altitude_m;
  const double blind = (h - c.sharer.band_low_m) / std::tan(25.2 * M_PI / 180.0);
  const double radius = rig.uav->edge_orbit_radius_m();
  EXPECT_NEAR(radius, blind + c.edge_beyond_blind_m, 1e-9);
  const Vec2 ugv(6.0, 2.0);  // facing south (the rig's statuses)
  rig.sky->ugvs = {ugv};
  const Vec2 front = ugv + Vec2(0.0, -radius);
  const auto ask = [&] {
    rig.status(0, ugv, msg::UgvMode::kWaitingForSupport);
    rig.request(0, ugv + Vec2(0.0, 1.7), 0.2, false, ugv + Vec2(0.0, -0.3));
  };
  for (int i = 0; i < 12 && rig.distance_to(front) > 1.0; ++i) {
    ask();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  ASSERT_LT(rig.distance_to(front), 1.0);  // in front of it first
  double nearest = 1e9, farthest = 0.0, turned = 0.0;
  double last = std::atan2(rig.sky->p.y() - ugv.y(), rig.sky->p.x() - ugv.x());
  for (int i = 0; i < 80; ++i) {
    if (i % 10 == 0) ask();
    rig.ex.run_until(rig.ex.now() + 100ms);
    nearest = std::min(nearest, rig.distance_to(ugv));
    farthest = std::max(farthest, rig.distance_to(ugv));
    const double bearing = std::atan2(rig.sky->p.y() - ugv.y(), rig.sky->p.x() - ugv.x());
    turned += std::remainder(bearing - last, 2.0 * M_PI);
    last = bearing;
  }
  EXPECT_EQ(rig.uav->mode(), UavMode::kHover);
  EXPECT_GT(nearest, blind);                // never over the ground it must see
  EXPECT_LT(farthest, radius + 0.8);        // within the camera's reach of the tag
  EXPECT_GT(std::abs(turned), M_PI / 2.0);  // round it: each side seen from that side
  // A UGV driving towards an obstacle 2 m ahead gets the usual orbit round its support point.
  rig.request(0, ugv, 0.0, /*cancel=*/true);
  const Vec2 other(-6.0, 2.0);
  rig.sky->ugvs = {ugv, other};
  for (int i = 0; i < 12 && rig.distance_to(other + Vec2(0, 2)) > 1.0; ++i) {
    rig.status(1, other);
    rig.request(1, other + Vec2(0, 2), 3.0);
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(other + Vec2(0, 2)), 1.0);
}

// A narrow camera (40 deg from 1.6 m up: tags within 1.1 m) never sees the tag of a UGV near the
// point the usual 2 m orbit circles. The UAV flies to the UGV first, then circles through it
// round its support point: the tag comes back into view every turn, the point is seen from
// several sides. With the field world's wide lens the orbit is the usual one (tested above).
TEST(UavSupervisorTask, ANarrowCameraCirclesThroughTheUgvItSupports) {
  UavSupervisorConfig c;
  c.camera_view = {5.0, 40.0, 0.3};
  c.lidar_pattern = {32, -25.2, 1.2, 1200};
  Rig rig(nullptr, c);
  const double reach = camera_reach(c.camera_view, rig.uav->config().flight.altitude_m);  // ~1.1 m
  ASSERT_LT(reach, c.orbit_radius_m);
  const Vec2 ugv(6.0, 2.0), support = ugv + Vec2(0.0, -1.5);  // facing south
  rig.sky->ugvs = {ugv};
  const auto ask = [&] {
    rig.status(0, ugv, msg::UgvMode::kWaitingForSupport);
    rig.request(0, support, 0.2, false, ugv + Vec2(0.0, -2.5));
  };
  for (int i = 0; i < 12 && rig.distance_to(ugv) > 0.8; ++i) {
    ask();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  ASSERT_LT(rig.distance_to(ugv), 0.8);                    // over the UGV first
  const Vec2 centre = ugv + Vec2(0.0, -c.orbit_radius_m);  // through it, round its support point
  double farthest = 0.0, turned = 0.0;
  bool left = false, back = false, hovering = true;
  double last = std::atan2(rig.sky->p.y() - centre.y(), rig.sky->p.x() - centre.x());
  for (int i = 0; i < 120; ++i) {  // 12 s: its hover timeout (10 s) lets others have a turn
    if (i % 10 == 0) ask();
    rig.ex.run_until(rig.ex.now() + 100ms);
    if (i < 80) hovering = hovering && rig.uav->mode() == UavMode::kHover;
    farthest = std::max(farthest, rig.distance_to(ugv));
    left = left || rig.distance_to(ugv) > 2.0 * reach;
    back = back || (left && rig.distance_to(ugv) < reach);
    const double bearing = std::atan2(rig.sky->p.y() - centre.y(), rig.sky->p.x() - centre.x());
    turned += std::remainder(bearing - last, 2.0 * M_PI);
    last = bearing;
  }
  EXPECT_TRUE(hovering);
  EXPECT_GT(farthest, 3.0);                 // round the far side of the support point
  EXPECT_TRUE(back);                        // and back over the tag
  EXPECT_GT(std::abs(turned), 1.5 * M_PI);  // a full turn round the point, near enough
}

// A UGV whose firmware restarted without a kept pose asks for its first relative pose where its
// mission starts; it has not driven since we last knew where it was: the UAV looks there first,
// and where it asks only once it hovered there in vain (it may have been carried away).
TEST(UavSupervisorTask, ALostUgvIsSoughtWhereItWasLastKnownThenWhereItAsks) {
  Rig rig;
  const Vec2 last(6.0, -4.0), start(-6.0, 6.0);
  rig.status(0, last);
  rig.ex.run_until(rig.ex.now() + 300ms);
  const auto lost = [&] {
    rig.status(0, start, msg::UgvMode::kWaitingForInit);
    rig.request(0, start, 0.0, false, start);
  };
  for (int i = 0; i < 12 && rig.distance_to(last) > 3.0; ++i) {
    lost();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(last), 3.0);
  EXPECT_GT(rig.distance_to(start), 10.0);
  for (int i = 0; i < 30 && rig.uav->health().hover_timeouts == 0; ++i) {  // not found there
    lost();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  ASSERT_EQ(rig.uav->health().hover_timeouts, 1u);
  for (int i = 0; i < 40 && rig.distance_to(start) > 3.0; ++i) {  // after the cooldown
    lost();
    rig.ex.run_until(rig.ex.now() + 1s);
  }
  EXPECT_LT(rig.distance_to(start), 3.0);
}

// Every UGV receives each UAV's odometry: 20 Hz (odometry_period), the newest sample each time,
// from a 50 Hz source and control loop.
TEST(UavSupervisorTask, SendsItsOdometryAtTwentyHertz) {
  Rig rig;
  Collect<msg::UavOdometry> odometry;
  ASSERT_TRUE(rig.bus->subscribe(msg::topic_of<msg::UavOdometry>, kAnyRobot, odometry));
  rig.ex.run_until(TimePoint{1s});
  const std::size_t before = odometry.got.size();
  rig.ex.run_until(TimePoint{3s});
  const std::size_t sent = odometry.got.size() - before;
  EXPECT_GE(sent, 38u);
  EXPECT_LE(sent, 41u);
  for (std::size_t i = before + 1; i < odometry.got.size(); ++i) {
    const Duration gap = odometry.got[i].stamp - odometry.got[i - 1].stamp;
    EXPECT_GE(gap, 40ms);
    EXPECT_LE(gap, 60ms);
  }
}

TEST(UavSupervisorTask, AFlightControllerThatLeavesTheMissionIsNoLongerCommandedAndSaysWhy) {
  Rig rig;
  Collect<msg::UavOdometry> odometry;
  ASSERT_TRUE(rig.bus->subscribe(msg::topic_of<msg::UavOdometry>, kAnyRobot, odometry));
  rig.ex.run_until(TimePoint{1s});
  ASSERT_FALSE(odometry.got.empty());
  EXPECT_EQ(odometry.got.back().flight, msg::UavFlight::kInControl);
  const std::size_t sent = rig.fc.count();
  ASSERT_GT(sent, 0u);
  rig.fc.set_status({msg::UavFlight::kLost, msg::FlightFault::kFailsafe});
  rig.ex.run_until(rig.ex.now() + 1s);
  EXPECT_EQ(odometry.got.back().flight, msg::UavFlight::kLost);
  EXPECT_EQ(odometry.got.back().fault, msg::FlightFault::kFailsafe);
  EXPECT_LE(rig.fc.count(), sent + 1);  // at most the setpoint of the tick it changed in
  EXPECT_EQ(rig.uav->health().flight_lost, 1u);
  EXPECT_EQ(rig.uav->flight_status().fault, msg::FlightFault::kFailsafe);

  // Its odometry gone too (the flight stack down): the flight state still reaches the UGVs, as
  // the last sample repeated, at once on a change and at 5 Hz after.
  rig.sky->odometry_on = false;
  rig.ex.run_until(rig.ex.now() + 100ms);
  const std::size_t before = odometry.got.size();
  const TimePoint last_stamp = odometry.got.back().stamp;
  rig.fc.set_status({msg::UavFlight::kLost, msg::FlightFault::kSilent});
  rig.ex.run_until(rig.ex.now() + 1s);
  ASSERT_GE(odometry.got.size(), before + 5);
  EXPECT_LE(odometry.got.size(), before + 7);
  EXPECT_EQ(odometry.got.back().stamp, last_stamp);  // no new pose is made up
  EXPECT_EQ(odometry.got.back().fault, msg::FlightFault::kSilent);
}

namespace {

// Two UAVs (ids 0 and 1) over one site on one bus, the UGVs played by the test.
struct TwoUavs {
  TwoUavs() {
    sim::MapGenConfig cfg;
    cfg.boxes = 40;
    cfg.seed = 3;
    world = sim::generate_box_world(cfg).value();
    bus = std::make_unique<platform::LoopbackTransport>(1);
    pump = std::make_unique<platform::TransportPump>(*bus);
    EXPECT_TRUE(ex.add({pump.get(), 10ms, 1ms}));
    for (std::size_t i = 0; i < 2; ++i) {
      lidar[i] = std::make_unique<hal::scripted::ScriptedLidar>();
      sky[i] = std::make_unique<Sky>(odom[i], *lidar[i], camera[i], fc[i], world);
      sky[i]->p = Vec3(i == 0 ? -12.0 : 12.0, 0.0, 1.0);
      UavSupervisorConfig c;
      c.id = static_cast<RobotId>(i);
      uav[i] = std::make_unique<UavSupervisorTask>(c, *bus, odom[i], *lidar[i], camera[i], fc[i]);
      EXPECT_TRUE(ex.add({sky[i].get(), 20ms, 5ms}));
      EXPECT_TRUE(ex.add(uav[i]->rows()));
    }
    EXPECT_TRUE(ex.init());
  }
  // Every UGV says where it is and asks for support at its point (a heartbeat, as UGVs do).
  void heartbeat(double t_pc) {
    for (std::size_t id = 0; id < ugvs.size(); ++id) {
      msg::UgvStatus s;
      s.stamp = ex.now();
      s.ugv_id = static_cast<RobotId>(id);
      s.mode = msg::UgvMode::kWaitingForSupport;
      s.position_m[0] = ugvs[id].x();
      s.position_m[1] = ugvs[id].y();
      ASSERT_TRUE(bus->publish(s));
      msg::CollisionInfo ci;
      ci.stamp = ex.now();
      ci.ugv_id = static_cast<RobotId>(id);
      ci.seq = ++seq;
      ci.support_point_m[0] = ugvs[id].x();
      ci.support_point_m[1] = ugvs[id].y() + 1.0;
      ci.collision_point_m[0] = ugvs[id].x();
      ci.collision_point_m[1] = ugvs[id].y() + 3.0;
      ci.time_to_collision_s = t_pc;
      ASSERT_TRUE(bus->publish(ci));
    }
  }
  std::vector<RobotId> held(std::size_t i) const {
    std::vector<RobotId> out;
    const msg::SupportPlan& p = uav[i]->plan();
    for (std::size_t k = 0; k < p.stops.count; ++k)
      out.push_back(p.stops[k].ugv_id);
    std::sort(out.begin(), out.end());
    return out;
  }

  sim::BoxWorld world;
  std::array<hal::scripted::ScriptedOdometrySource, 2> odom;
  std::array<std::unique_ptr<hal::scripted::ScriptedLidar>, 2> lidar;
  std::array<hal::scripted::ScriptedRelativePoseSensor, 2> camera;
  std::array<hal::scripted::RecordingFlightController, 2> fc;
  std::unique_ptr<platform::LoopbackTransport> bus;
  std::array<std::unique_ptr<Sky>, 2> sky;
  std::array<std::unique_ptr<UavSupervisorTask>, 2> uav;
  std::unique_ptr<platform::TransportPump> pump;
  platform::LockstepExecutor ex;
  std::vector<Vec2> ugvs;
  std::uint32_t seq = 0;
};

}  // namespace

// Each UAV serves the UGVs near it and no UGV is in both plans; when one UAV's flight controller
// leaves the mission, the other takes its UGVs over.
TEST(UavSupervisorTask, TwoUavsSplitTheRequestsAndOneTakesOverWhenTheOtherIsLost) {
  TwoUavs f;
  f.ugvs = {Vec2(-13, -5), Vec2(-11, 5), Vec2(13, -5), Vec2(11, 5)};
  for (int i = 0; i < 3; ++i) {
    f.heartbeat(30.0 - i);
    f.ex.run_until(f.ex.now() + 1s);
  }
  EXPECT_EQ(f.held(0), (std::vector<RobotId>{0, 1}));
  EXPECT_EQ(f.held(1), (std::vector<RobotId>{2, 3}));
  EXPECT_GT(f.uav[0]->health().fleet_schedules, 10u);
  EXPECT_GT(f.uav[1]->health().fleet_schedules, 10u);
  EXPECT_EQ(f.uav[0]->health().peer_messages_rejected, 0u);
  // UAV 1 fails safe: within a second UAV 0 holds every request.
  f.fc[1].set_status({msg::UavFlight::kLost, msg::FlightFault::kFailsafe});
  for (int i = 0; i < 2; ++i) {
    f.heartbeat(27.0 - i);
    f.ex.run_until(f.ex.now() + 1s);
  }
  EXPECT_EQ(f.held(0), (std::vector<RobotId>{0, 1, 2, 3}));
  EXPECT_EQ(f.uav[0]->health().peers_lost, 1u);
}

// A UAV that goes silent (no odometry, no plans: a crash, a dead link) is gone after
// peer_timeout: its UGVs are taken over.
TEST(UavSupervisorTask, ASilentUavsUgvsAreTakenOverAfterThePeerTimeout) {
  TwoUavs f;
  f.ugvs = {Vec2(-13, -5), Vec2(13, -5)};
  for (int i = 0; i < 2; ++i) {
    f.heartbeat(30.0 - i);
    f.ex.run_until(f.ex.now() + 1s);
  }
  ASSERT_EQ(f.held(0), (std::vector<RobotId>{0}));
  ASSERT_EQ(f.held(1), (std::vector<RobotId>{1}));
  f.sky[1]->odometry_on = false;  // nothing new from UAV 1 (its plans still say it holds UGV 1)
  f.heartbeat(28.0);
  f.ex.run_until(f.ex.now() + 1s);
  EXPECT_EQ(f.held(0), (std::vector<RobotId>{0}));  // not yet: 1 s < peer_timeout
  for (int i = 0; i < 3; ++i) {
    f.heartbeat(27.0 - i);
    f.ex.run_until(f.ex.now() + 1s);
  }
  EXPECT_EQ(f.held(0), (std::vector<RobotId>{0, 1}));
}

// With two UAVs each UGV's nearby list comes from the UAV nearest to it (not from both: that
// doubled the lists every UGV receives), and from the other once that one falls silent.
TEST(UavSupervisorTask, EachUgvsNearbyListComesFromTheNearestUav) {
  TwoUavs f;
  f.ugvs = {Vec2(-13, -5), Vec2(-11, 5), Vec2(13, -5), Vec2(11, 5)};
  f.heartbeat(30.0);
  f.ex.run_until(f.ex.now() + 1s);
  const auto sent = [&] {
    return std::array<std::uint64_t, 2>{f.uav[0]->health().nearby_sent,
                                        f.uav[1]->health().nearby_sent};
  };
  Collect<msg::NearbyUgvs> lists;
  ASSERT_TRUE(f.bus->subscribe(msg::topic_of<msg::NearbyUgvs>, kAnyRobot, lists));
  const auto before = sent();
  for (int i = 0; i < 2; ++i) {
    f.heartbeat(29.0 - i);
    f.ex.run_until(f.ex.now() + 1s);
  }
  const auto after = sent();
  // 10 Hz for each of its two UGVs, 2 s (a step either way at the edges).
  EXPECT_NEAR(static_cast<double>(after[0] - before[0]), 40.0, 2.0);
  EXPECT_NEAR(static_cast<double>(after[1] - before[1]), 40.0, 2.0);
  for (const msg::NearbyUgvs& m : lists.got)
    EXPECT_EQ(m.uav_id, m.ugv_id < 2 ? 0 : 1) << "UGV " << m.ugv_id;
  // UAV 1 silent: after peer_timeout UAV 0 relays to all four.
  f.sky[1]->odometry_on = false;
  for (int i = 0; i < 4; ++i) {
    f.heartbeat(27.0 - i);
    f.ex.run_until(f.ex.now() + 1s);
  }
  const auto later = sent();
  f.heartbeat(23.0);
  f.ex.run_until(f.ex.now() + 1s);
  EXPECT_NEAR(static_cast<double>(sent()[0] - later[0]), 40.0, 2.0);  // 4 UGVs, 1 s
}

// Scheduling with a peer (its odometry and plans read, the split solved) allocates nothing.
TEST(UavSupervisorTask, TwoUavsStepsAllocateNothingInSteadyState) {
  TwoUavs f;
  f.ugvs = {Vec2(-13, -5), Vec2(-11, 5), Vec2(13, -5), Vec2(11, 5)};
  f.heartbeat(30.0);
  f.ex.run_until(f.ex.now() + 2s);
  const std::uint64_t before = f.uav[0]->health().fleet_schedules;
  {
    test::AllocationCounter counter;
    for (int i = 0; i < 1000; ++i) {
      if (i % 100 == 0) f.heartbeat(28.0);
      f.ex.step();
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_GT(f.uav[0]->health().fleet_schedules, before + 10);
}

namespace {

// A clock exchange's end on its own clock (`ahead` of the test's), stepped while `on`: the time
// server's (uav::ClockServer) or a UGV's (platform::UgvFleetClock).
template <class Clock>
class ClockEnd final : public platform::Task {
 public:
  ClockEnd(platform::Transport& bus, RobotId id, Duration ahead_of_test)
      : ahead(ahead_of_test), bus_(bus), id_(id) {}
  const char* name() const override { return "clock_end"; }
  Status init(TimePoint) override { return clock.attach(bus_, id_); }
  void step(TimePoint now) override {
    if (on) clock.step(now + ahead);
  }
  const Duration ahead;
  bool on = false;
  Clock clock;

 private:
  platform::Transport& bus_;
  RobotId id_;
};

constexpr Duration kServerAhead = std::chrono::hours(1);  // UAV 0's clock: fleet time

}  // namespace

// UAV 1 is not the time server: until it has heard UAV 0's clock it sends nothing stamped (its
// own clock is not fleet time) and reads nothing stamped; then every stamp it sends is fleet time,
// and what the UGVs stamp in fleet time is understood.
TEST(UavSupervisorTask, AUavThatIsNotTheTimeServerSpeaksFleetTime) {
  UavSupervisorConfig config;
  config.id = 1;
  Rig rig(nullptr, config);
  ClockEnd<ClockServer> server(*rig.bus, 0, kServerAhead);
  ASSERT_TRUE(rig.ex.add({&server, 20ms, 2ms}));
  ASSERT_TRUE(rig.ex.init());
  rig.sky->ugvs = {Vec2(1.0, 0.0)};  // in view
  rig.ex.run_until(rig.ex.now() + 1s);
  EXPECT_TRUE(rig.rpes.got.empty());
  EXPECT_TRUE(rig.patches.got.empty());
  EXPECT_GT(rig.uav->health().unsynchronised, 0u);
  EXPECT_FALSE(rig.uav->fleet_clock().has_estimate());

  server.on = true;
  rig.ex.run_until(rig.ex.now() + 500ms);
  ASSERT_TRUE(rig.uav->fleet_clock().has_estimate());
  const auto fleet_now = [&] { return rig.ex.now() + kServerAhead; };
  // A UGV's status and request, stamped in fleet time.
  msg::UgvStatus st;
  st.stamp = fleet_now();
  st.position_m[0] = 1.0;
  st.yaw_rad = -M_PI / 2;
  ASSERT_TRUE(rig.bus->publish(st));
  msg::CollisionInfo ci;
  ci.stamp = fleet_now();
  ci.ugv_id = 0;
  ci.seq = 1;
  ci.support_point_m[0] = 3.0;
  ci.collision_point_m[0] = 3.0;
  ci.time_to_collision_s = 5.0;
  ASSERT_TRUE(rig.bus->publish(ci));
  const TimePoint asked = fleet_now();
  rig.ex.run_until(rig.ex.now() + 1s);
  // Sent in this second of fleet time (to the conversion's few milliseconds), not an hour off.
  const auto in_this_second = [&](TimePoint stamp) {
    return stamp >= asked - 10ms && stamp <= fleet_now() + 10ms;
  };
  ASSERT_FALSE(rig.rpes.got.empty());
  EXPECT_TRUE(in_this_second(rig.rpes.got.back().stamp));
  ASSERT_FALSE(rig.plans.got.empty());
  EXPECT_TRUE(in_this_second(rig.plans.got.back().stamp));
  ASSERT_EQ(rig.plans.got.back().stops.count, 1u);  // the request was understood
  EXPECT_EQ(rig.plans.got.back().stops[0].ugv_id, 0);
  EXPECT_EQ(rig.uav->health().stamps.from_future + rig.uav->health().stamps.too_old, 0u);
}

// The time server (UAV 0) is lost. A UGV that was synchronised keeps its estimate; one that starts
// afterwards (a restarted ugv_fw) learns fleet time from UAV 1, which stands in with the fleet
// time it learnt, and only once it has not heard the server for a while.
TEST(UavSupervisorTask, AnotherUavStandsInForALostTimeServer) {
  UavSupervisorConfig config;
  config.id = 1;
  Rig rig(nullptr, config);
  ClockEnd<ClockServer> server(*rig.bus, 0, kServerAhead);
  ClockEnd<platform::UgvFleetClock> early(*rig.bus, 3, -7s), late(*rig.bus, 4, -7s);
  ASSERT_TRUE(rig.ex.add({&server, 20ms, 2ms}));
  ASSERT_TRUE(rig.ex.add({&early, 20ms, 2ms}));
  ASSERT_TRUE(rig.ex.add({&late, 20ms, 2ms}));
  ASSERT_TRUE(rig.ex.init());
  server.on = early.on = true;
  rig.ex.run_until(rig.ex.now() + 2s);
  const auto fleet_now = [&] { return rig.ex.now() + kServerAhead; };
  ASSERT_TRUE(early.clock.synchronised(rig.ex.now() + early.ahead));
  EXPECT_EQ(early.clock.standby_exchanges(), 0u);  // UAV 1 hears the server: it does not answer
  ASSERT_TRUE(rig.uav->fleet_clock().synchronised(rig.ex.now()));

  server.on = false;  // lost
  late.on = true;
  rig.ex.run_until(rig.ex.now() + 2s);
  EXPECT_FALSE(late.clock.has_estimate());  // not yet: the server was heard 2 s ago
  rig.ex.run_until(rig.ex.now() + 2s);
  ASSERT_TRUE(late.clock.synchronised(rig.ex.now() + late.ahead));
  EXPECT_GT(late.clock.standby_exchanges(), 0u);
  EXPECT_EQ(early.clock.standby_exchanges(), 0u);  // synchronised: it kept its own estimate
  // Both convert fleet time to their clocks to within milliseconds.
  for (const auto* j : {&early, &late}) {
    const double off_s = to_seconds(j->clock.to_local(fleet_now()) - (rig.ex.now() + j->ahead));
    EXPECT_LT(std::abs(off_s), 0.005) << j->clock.standby_exchanges();
  }
}
