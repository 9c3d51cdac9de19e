#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <memory>

#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/world/cloud_world.hpp"
#include "colag/sim/world/pcd_loader.hpp"
#include "colag/sim/world/sim_world.hpp"

using namespace colag;
using namespace colag::sim;
using namespace std::chrono_literals;

TEST(PcdLoader, ReadsAsciiAndBinaryAndFindsTheBoxes) {
  const std::string header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 "
      "1\n"
      "WIDTH 4\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ";
  std::vector<Vec3> pts;
  std::string error;
  ASSERT_TRUE(parse_pcd(
      header + "ascii\n1.05 2.05 0.3 7\n1.15 2.05 0.6 7\n5 5 0 1\n-3.05 0.05 0.2 1\n", pts, error))
      << error;
  ASSERT_EQ(pts.size(), 4u);
  EXPECT_FLOAT_EQ(static_cast<float>(pts[1].z()), 0.6F);
  const BoxWorld w = box_world_from_points(pts);
  // Three columns above the ground, each as tall as its points (the ground point is ignored).
  ASSERT_EQ(w.boxes.size(), 3u);
  // Binary: the same records as little-endian floats.
  std::string bin = header + "binary\n";
  const float rec[4][4] = {
      {1.05F, 2.05F, 0.3F, 7}, {1.15F, 2.05F, 0.6F, 7}, {5, 5, 0, 1}, {-3.05F, 0.05F, 0.2F, 1}};
  bin.append(reinterpret_cast<const char*>(rec), sizeof rec);
  ASSERT_TRUE(parse_pcd(bin, pts, error)) << error;
  EXPECT_FLOAT_EQ(static_cast<float>(pts[3].x()), -3.05F);
}

TEST(PcdLoader, MalformedFilesGiveClearErrors) {
  std::vector<Vec3> pts;
  std::string error;
  EXPECT_FALSE(parse_pcd(
      "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nPOINTS 1\nDATA ascii\n1 2\n", pts,
      error));
  EXPECT_NE(error.find("x, y and z"), std::string::npos) << error;
  EXPECT_FALSE(
      parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 2\nDATA ascii\n1 2 3\n", pts, error));
  EXPECT_NE(error.find("1 points"), std::string::npos) << error;
  EXPECT_FALSE(parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 two 3\n",
                         pts, error));
  EXPECT_NE(error.find("expected 3 numbers"), std::string::npos) << error;
  EXPECT_FALSE(
      parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 10\nDATA binary\nabc", pts, error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  EXPECT_FALSE(parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA binary_compressed\n",
                         pts, error));
  EXPECT_NE(error.find("not supported"), std::string::npos) << error;
  // Found by fuzz_pcd: far points overflowed the column arithmetic; absurd sizes the record size.
  EXPECT_FALSE(parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1e300 0 1\n",
                         pts, error));
  EXPECT_NE(error.find("1000 km"), std::string::npos) << error;
  EXPECT_FALSE(
      parse_pcd("FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 0 1\n", pts, error));
  EXPECT_NE(error.find("SIZE must be"), std::string::npos) << error;
  EXPECT_FALSE(
      parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 99999999\nPOINTS 1\n"
                "DATA binary\nabc",
                pts, error));
  EXPECT_NE(error.find("COUNT must be"), std::string::npos) << error;
  EXPECT_FALSE(
      parse_pcd("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 9999999999\nHEIGHT "
                "9999999999\nDATA ascii\n",
                pts, error));
  EXPECT_NE(error.find("absurd"), std::string::npos) << error;
  EXPECT_FALSE(parse_pcd("FIELDS x y z\nSIZE 4 4 4\n", pts, error));
  EXPECT_NE(error.find("DATA"), std::string::npos) << error;
  EXPECT_FALSE(
      parse_pcd("FIELDS x y z\nSIZE 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2 3\n", pts, error));
  EXPECT_FALSE(parse_pcd("BOGUS 1\n", pts, error));
  EXPECT_FALSE(load_pcd("/nonexistent.pcd", pts, error));
}

// The project's own evaluation maps ship with it (sim/maps/, written by colag_sim --save-map):
// a clone has them, and reading one back gives exactly the boxes the scenario generates.
TEST(PcdLoader, TheShippedDenseMapReadsBackAsItsEightyBoxes) {
  std::vector<Vec3> pts;
  std::string error;
  ASSERT_TRUE(load_pcd(COLAG_SIM_MAPS "/dense_seed1.pcd", pts, error)) << error;
  const BoxWorld loaded = box_world_from_points(pts);
  MapGenConfig gen;
  gen.boxes = 80;
  gen.seed = 1;
  const BoxWorld generated = generate_box_world(gen).value();
  ASSERT_EQ(loaded.boxes.size(), generated.boxes.size());
  for (const Box& g : generated.boxes) {
    int matches = 0;
    for (const Box& l : loaded.boxes) {
      if ((l.center - g.center).norm() < 1e-6 && (l.half_size - g.half_size).norm() < 1e-6 &&
          std::abs(l.height_m - g.height_m) < 1e-6)
        ++matches;
    }
    EXPECT_EQ(matches, 1) << "box at (" << g.center.x() << ", " << g.center.y() << ")";
  }
  ASSERT_TRUE(load_pcd(COLAG_SIM_MAPS "/sparse_seed1.pcd", pts, error)) << error;
  EXPECT_EQ(box_world_from_points(pts).boxes.size(), 40u);
}

// The paper's own map, where it is beside the project.
TEST(PcdLoader, ThePapersDenseMapHasItsEightyBoxes) {
  std::vector<Vec3> pts;
  std::string error;
  if (!std::ifstream(COLAG_SHARED_MAPS "/80obs.pcd"))
    GTEST_SKIP() << "no " COLAG_SHARED_MAPS "/80obs.pcd here";
  ASSERT_TRUE(load_pcd(COLAG_SHARED_MAPS "/80obs.pcd", pts, error)) << error;
  const BoxWorld w = box_world_from_points(pts);
  ASSERT_EQ(w.boxes.size(), 80u);
  int small = 0;
  for (const Box& b : w.boxes) {
    const double side = 2 * b.half_size.x();
    EXPECT_TRUE(std::abs(side - 0.7) < 1e-6 || std::abs(side - 0.9) < 1e-6) << side;
    EXPECT_NEAR(b.height_m, 0.6, 1e-6);
    small += std::abs(side - 0.7) < 1e-6;
  }
  EXPECT_EQ(small, 45);
}

namespace {
struct Rig {
  Rig() {
    world.boxes.push_back({Vec2(3.0, 0.0), Vec2(0.5, 0.5), 0.6});
    sim = std::make_unique<SimWorld>(SimWorldConfig{}, world, clock);
  }
  void run(double seconds, double v, double omega, hal::can::CanDrive& drive) {
    for (int i = 0; i < static_cast<int>(seconds * 50); ++i) {
      clock.advance(20ms);
      (void)drive.command({clock.now(), v, omega});
      sim->step(clock.now(), 0.02);
    }
  }
  BoxWorld world;
  hal::scripted::ManualClock clock;
  std::unique_ptr<SimWorld> sim;
};
}  // namespace

TEST(SimWorld, AUgvDrivesOverCanAndItsEncodersReportIt) {
  Rig rig;
  const int u = rig.sim->add_ugv({Vec2(0, 3), 0.0});
  hal::can::CanDrive drive(rig.sim->ugv_can(u), {}, {});
  hal::can::CanWheelOdometry odo(rig.sim->ugv_can(u), {}, {});
  // 4 s at 0.5 m/s after a 0.5 s ramp at 1 m/s^2: 2.0 - 0.125 m. Polled every 20 ms, as the
  // UGV task does.
  double travelled = 0;
  int n = 0;
  for (int i = 0; i < 200; ++i) {
    rig.run(0.02, 0.5, 0.0, drive);
    hal::WheelOdometrySample s;
    while (odo.poll(s)) {
      travelled += s.v_mps * 0.02;
      ++n;
    }
  }
  EXPECT_NEAR(rig.sim->ugv(u).pose().p.x(), 1.875, 0.05);
  EXPECT_GE(n, 199);
  EXPECT_NEAR(travelled, 1.875, 0.05);  // the encoders saw the same distance
  EXPECT_EQ(odo.counters().bad_checksum + odo.counters().lost_frames + odo.counters().implausible,
            0u);
}

TEST(SimWorld, ACollisionIsRecordedAndTheUgvStops) {
  Rig rig;
  const int u = rig.sim->add_ugv({Vec2(0, 0), 0.0});
  hal::can::CanDrive drive(rig.sim->ugv_can(u), {}, {});
  rig.run(8.0, 0.5, 0.0, drive);  // straight into the box at x = 2.5
  ASSERT_EQ(rig.sim->collisions().size(), 1u);
  EXPECT_EQ(rig.sim->collisions()[0].ugv, u);
  EXPECT_TRUE(rig.sim->ugv(u).frozen());
  EXPECT_LT(rig.sim->ugv(u).pose().p.x(), 2.3);  // stopped where it hit (radius 0.25)
  EXPECT_LT(rig.sim->min_clearance_m(u), 0.0);
}

TEST(SimWorld, TheCameraSeesUgvsInRangeAndInSightOnly) {
  Rig rig;
  rig.sim->add_uav(Vec3(0, 0, 1));
  rig.sim->add_ugv({Vec2(1.0, 1.0), 0.3});  // near
  rig.sim->add_ugv(
      {Vec2(4.5, 0.0), 0.0});  // behind the box (seen from 1 m up? no: the box is 0.6 m)
  rig.sim->add_ugv({Vec2(-9.0, 0.0), 0.0});  // too far
  rig.clock.advance(20ms);
  rig.sim->step(rig.clock.now(), 0.02);
  hal::RelativePoseDetection d[8];
  const std::size_t n = rig.sim->uav_camera().poll(d);
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(d[0].ugv_id, 0);
  EXPECT_NEAR(d[0].ugv_in_uav.p.x(), 1.0, 1.0);  // 0.2 m noise: within 5 sigma
  EXPECT_FALSE(rig.sim->line_of_sight(Vec3(0, 0, 1), Vec3(4.5, 0, 0.3)));
}

TEST(LidarSimulator, TwoThreadsCastTheSameScanAsOne) {
  sim::MapGenConfig gen;
  const sim::BoxWorld world = sim::generate_box_world(gen).value();
  platform::WorkerPool pool(1);
  sim::LidarSimulator one, two({}, &pool);
  const Pose3 pose{Vec3(0.4, 3.1, 1.0), quat_from_yaw(0.7)};
  std::span<const hal::LidarPoint> p1, m1, p2, m2;
  one.scan(world, pose, p1, m1);
  two.scan(world, pose, p2, m2);
  ASSERT_GT(p1.size(), 1000u);
  ASSERT_EQ(p1.size(), p2.size());
  ASSERT_EQ(m1.size(), m2.size());
  EXPECT_EQ(std::memcmp(p1.data(), p2.data(), p1.size_bytes()), 0);
  EXPECT_EQ(std::memcmp(m1.data(), m2.data(), m1.size_bytes()), 0);
}

// The culling (boxes per column, no box tests for beams above every box in range) and the
// per-core blocks of columns change nothing: every beam, in column order, is where casting it
// against the ground and every box of the world puts it. From above the boxes, from among
// them (below their tops), and tilted.
TEST(LidarSimulator, CastsWhereTestingEveryBoxWould) {
  sim::MapGenConfig gen;
  gen.boxes = 80;
  const sim::BoxWorld world = sim::generate_box_world(gen).value();
  platform::WorkerPool pool(1);
  sim::LidarSimulator lidar({}, &pool);
  const LidarPattern& pat = lidar.pattern();
  const Quat tilted(Eigen::AngleAxisd(0.08, Vec3::UnitX()) * Eigen::AngleAxisd(2.2, Vec3::UnitZ()));
  for (const Pose3& pose :
       {Pose3{Vec3(0.4, 3.1, 1.0), quat_from_yaw(0.7)},
        Pose3{Vec3(-3.0, -5.0, 0.4), quat_from_yaw(-1.9)}, Pose3{Vec3(2.0, 1.0, 1.3), tilted}}) {
    std::span<const hal::LidarPoint> points, misses;
    lidar.scan(world, pose, points, misses);
    const Mat3 R = pose.q.toRotationMatrix();
    std::vector<Vec3> want_points, want_misses;
    for (int c = 0; c < pat.columns; ++c) {
      const double az = 2.0 * M_PI * c / pat.columns;
      for (int b = 0; b < pat.beams; ++b) {
        const double el = (pat.lowest_elevation_deg + b * pat.elevation_step_deg) * M_PI / 180.0;
        const Vec3 local(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        const Vec3 dir = R * local;
        double t = dir.z() < -1e-9 ? -pose.p.z() / dir.z() : 1e9;
        for (const Box& box : world.boxes) {
          const double tb = ray_box(pose.p, dir, box);
          if (tb >= 0.0 && tb < t) t = tb;
        }
        if (t < pat.min_range_m) continue;
        (t <= pat.max_range_m ? want_points : want_misses)
            .push_back(local * std::min(t, pat.max_range_m));
      }
    }
    ASSERT_EQ(points.size(), want_points.size());
    ASSERT_EQ(misses.size(), want_misses.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec3 got(points[i].x_m, points[i].y_m, points[i].z_m);
      worst = std::max(worst, (got - want_points[i]).norm());
    }
    for (std::size_t i = 0; i < misses.size(); ++i) {
      const Vec3 got(misses[i].x_m, misses[i].y_m, misses[i].z_m);
      worst = std::max(worst, (got - want_misses[i]).norm());
    }
    EXPECT_LT(worst, 1e-5) << pose.p.transpose();  // float output
  }
}

// The field world's wheels: each encoder counts its own wheel with its own scale error, so a
// robot driving straight reports the scaled distance and a turn that did not happen.
TEST(SimWorld, FieldWheelsReportScaledDistanceAndAPhantomTurn) {
  Rig rig;
  WheelErrors wheels;
  wheels.left_scale = 0.05;
  wheels.right_scale = -0.05;
  const int u = rig.sim->add_ugv({Vec2(0, 3), 0.0}, {}, &wheels);
  hal::can::CanDrive drive(rig.sim->ugv_can(u), {}, {});
  hal::can::CanWheelOdometry odo(rig.sim->ugv_can(u), {}, {});
  double travelled = 0, turned = 0;
  for (int i = 0; i < 200; ++i) {
    rig.run(0.02, 0.5, 0.0, drive);
    hal::WheelOdometrySample s;
    while (odo.poll(s)) {
      travelled += s.v_mps * 0.02;
      turned += s.omega_radps * 0.02;
    }
  }
  EXPECT_NEAR(rig.sim->ugv(u).pose().p.x(), 1.875, 0.05);  // the body went straight
  EXPECT_NEAR(rig.sim->ugv(u).pose().yaw_rad, 0.0, 0.05);
  EXPECT_NEAR(travelled, 1.875, 0.05);  // the mean scale is 1
  // (right - left) / track: -0.1 x 1.875 m / track, seen as a turn to the right.
  const double track = hal::can::WheelGeometry{}.track_width_m;
  EXPECT_NEAR(turned, -0.1 * 1.875 / track, 0.05);
}

// The field world's camera: tags missed, outliers, frames late by the latency.
TEST(SimWorld, FieldCameraMissesSomeTagsThrowsSomeOutliersAndIsLate) {
  SimWorldConfig cfg;
  cfg.camera.miss_probability = 0.1;
  cfg.camera.outlier_probability = 0.05;
  cfg.camera.outlier_max_m = 3.0;  // 0.9-3 m off: far beyond the 0.2 m noise
  cfg.camera.latency = 100ms;
  cfg.camera.period = 60ms;  // on the 20 ms step grid
  BoxWorld empty;
  hal::scripted::ManualClock clock;
  SimWorld sim(cfg, empty, clock);
  sim.add_uav(Vec3(0, 0, 1));
  sim.add_ugv({Vec2(0.5, 0.0), 0.0});
  int detections = 0, far_off = 0;
  Duration worst_age{}, best_age = 1h;
  for (int i = 0; i < 4000; ++i) {
    clock.advance(20ms);
    sim.step(clock.now(), 0.02);
    hal::RelativePoseDetection d[4];
    const std::size_t n = sim.uav_camera().poll(d);
    if (clock.now() < TimePoint{200ms}) continue;
    for (std::size_t k = 0; k < n; ++k) {
      ++detections;
      worst_age = std::max(worst_age, clock.now() - d[k].stamp);
      best_age = std::min(best_age, clock.now() - d[k].stamp);
      if ((d[k].ugv_in_uav.p.head<2>() - Vec2(0.5, 0.0)).norm() > 0.8) ++far_off;  // 4 sigma
    }
  }
  const int captured = static_cast<int>(to_seconds(clock.now() - TimePoint{200ms}) / 0.06);
  EXPECT_NEAR(detections, 0.9 * captured, 0.03 * captured);  // 10 % missed
  EXPECT_GT(far_off, 0.03 * detections);                     // 5 % outliers
  EXPECT_LT(far_off, 0.07 * detections);
  EXPECT_GE(best_age, 100ms);  // delivered no earlier than the latency
  EXPECT_LE(worst_age, 160ms);
}
