// The board programs' YAML configuration: values, defaults, and errors that name the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "colag/board/program.hpp"
#include "colag/uav/app/uav_config.hpp"
#include "colag/ugv/app/ugv_config.hpp"

namespace colag::board {
using uav::load_uav_config;
using uav::UavBoardConfig;
using ugv::load_ugv_config;
using ugv::UgvBoardConfig;
namespace {

class BoardConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("colag_board_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::string ugv_error(const std::string& text) {
    UgvBoardConfig c;
    std::string error;
    EXPECT_FALSE(load_ugv_config(write("ugv.yaml", text), c, error)) << text;
    return error;
  }
  std::filesystem::path dir_;
};

TEST_F(BoardConfig, ReadsEveryUgvKey) {
  UgvBoardConfig c;
  std::string error;
  ASSERT_TRUE(load_ugv_config(write("ugv.yaml", R"(
robot: {id: 3, goal: [2.0, -16.0], via: [[5, 8], [-1, 0.5]], start_guess: [2.0, 16.0, -1.57],
        radius_m: 0.3,
        state_file: /var/lib/colag/ugv3.state, state_max_age_s: 60}
dds: {domain: 7, partition: lab}
realtime: {fifo_priority: 60, lock_memory: false}
can: {interface: vcan1, counts_id: 0x301, speeds_id: 0x302, command_id: 0x401}
wheels: {radius_m: 0.08, track_m: 0.5, ticks_per_rev: 2048, max_speed_mps: 1.2}
rates: {control_hz: 100, planning_hz: 5}
odometry: {timeout_ms: 80, sigma_v: 0.05, sigma_omega: 0.04,
           calibration: {estimate: true, scale: 0.01, turn_scale: 0.05, drift_per_m: 0.02,
                         drift_per_s: 0.002, turn_walk: 0.05}}
)"),
                              c, error))
      << error;
  EXPECT_EQ(c.nav.id, 3);
  EXPECT_EQ(c.nav.goal, Vec2(2.0, -16.0));
  ASSERT_EQ(c.nav.via.size(), 2u);
  EXPECT_EQ(c.nav.via[1], Vec2(-1.0, 0.5));
  EXPECT_TRUE(c.nav.has_start_guess);
  EXPECT_DOUBLE_EQ(c.nav.start_guess.yaw_rad, -1.57);
  EXPECT_DOUBLE_EQ(c.nav.body_radius_m, 0.3);
  EXPECT_EQ(c.common.dds_domain, 7u);
  EXPECT_EQ(c.common.dds_partition, "lab");
  EXPECT_EQ(c.common.realtime.fifo_priority, 60);
  EXPECT_FALSE(c.common.realtime.lock_memory);
  EXPECT_EQ(c.can_interface, "vcan1");
  EXPECT_EQ(c.base.colag.counts_id, 0x301u);
  EXPECT_EQ(c.base.colag.command_id, 0x401u);
  EXPECT_DOUBLE_EQ(c.wheels.wheel_radius_m, 0.08);
  EXPECT_EQ(c.wheels.ticks_per_revolution, 2048u);
  EXPECT_EQ(c.nav.schedule.control.period, std::chrono::milliseconds(10));
  EXPECT_EQ(c.nav.schedule.planning.period, std::chrono::milliseconds(200));
  // A budget keeps its share of the period; the transport is polled at every control tick.
  EXPECT_EQ(c.nav.schedule.control.budget, std::chrono::microseconds(2500));
  EXPECT_EQ(c.nav.schedule.planning.budget, std::chrono::milliseconds(100));
  EXPECT_EQ(c.nav.schedule.transport.period, std::chrono::milliseconds(10));
  EXPECT_EQ(c.nav.odometry_timeout, std::chrono::milliseconds(80));
  EXPECT_DOUBLE_EQ(c.nav.ekf.noise.sigma_v_mps, 0.05);
  EXPECT_TRUE(c.nav.ekf.calibration.estimate);
  EXPECT_DOUBLE_EQ(c.nav.ekf.calibration.sigma_scale_v, 0.01);
  EXPECT_DOUBLE_EQ(c.nav.ekf.calibration.sigma_scale_omega, 0.05);
  EXPECT_DOUBLE_EQ(c.nav.ekf.calibration.sigma_omega_per_m_radpm, 0.02);
  EXPECT_DOUBLE_EQ(c.nav.ekf.calibration.sigma_omega_bias_radps, 0.002);
  EXPECT_DOUBLE_EQ(c.nav.ekf.calibration.walk_turn_per_sqrt_rad, 0.05);
  EXPECT_EQ(c.state_file, "/var/lib/colag/ugv3.state");
  EXPECT_DOUBLE_EQ(c.state_max_age_s, 60.0);
}

TEST_F(BoardConfig, DdsSecurityFilesAreRelativeToTheConfigAndAllRequired) {
  UgvBoardConfig c;
  std::string error;
  for (const char* f : {"pki/ca.pem", "pki/ugv1/identity.pem", "pki/ugv1/key.pem",
                        "pki/governance.p7s", "pki/ugv1/permissions.p7s", "abs/ca.pem"}) {
    std::filesystem::create_directories((dir_ / f).parent_path());
    write(f, "x");
  }
  const std::string absolute_ca = (dir_ / "abs/ca.pem").string();
  ASSERT_TRUE(load_ugv_config(write("secure.yaml", R"(
robot: {id: 1, goal: [0.0, -16.0]}
dds:
  security:
    identity_ca: pki/ca.pem
    certificate: pki/ugv1/identity.pem
    private_key: pki/ugv1/key.pem
    permissions_ca: )" + absolute_ca + R"(
    governance: pki/governance.p7s
    permissions: pki/ugv1/permissions.p7s
)"),
                              c, error))
      << error;
  EXPECT_TRUE(c.common.dds_security.enabled());
  EXPECT_EQ(c.common.dds_security.identity_ca, (dir_ / "pki/ca.pem").string());
  EXPECT_EQ(c.common.dds_security.permissions_ca, absolute_ca);
  EXPECT_EQ(c.common.dds_security.permissions, (dir_ / "pki/ugv1/permissions.p7s").string());
  EXPECT_NE(ugv_error("dds: {security: {identity_ca: ca.pem}}")
                .find("dds.security.certificate: required when security is on"),
            std::string::npos);
  EXPECT_NE(ugv_error("dds: {security: {cert: a.pem}}").find("dds.security.cert: unknown key"),
            std::string::npos);
  // --check-config must catch a file that is not there.
  EXPECT_NE(ugv_error(R"(
robot: {id: 1, goal: [0.0, -16.0]}
dds:
  security:
    identity_ca: pki/ca.pem
    certificate: pki/ugv1/nothere.pem
    private_key: pki/ugv1/key.pem
    permissions_ca: pki/ca.pem
    governance: pki/governance.p7s
    permissions: pki/ugv1/permissions.p7s
)")
                .find("dds.security.certificate: cannot read"),
            std::string::npos);
  EXPECT_TRUE(load_ugv_config(
      write("plain.yaml", "robot: {id: 1, goal: [0.0, -16.0]}\ndds: {domain: 3}"), c, error))
      << error;
  EXPECT_FALSE(c.common.dds_security.enabled());
}

TEST_F(BoardConfig, OnlyWhatTheOperatorMustSayIsRequired) {
  // An empty file would drive UGV 1 to (0, 0): which robot and where to go have no default.
  EXPECT_NE(ugv_error("").find("robot.id: required"), std::string::npos);
  EXPECT_NE(ugv_error("robot: {id: 2}").find("robot.goal: required"), std::string::npos);
  EXPECT_NE(ugv_error("robot: {goal: [0, -16]}").find("robot.id: required"), std::string::npos);
  EXPECT_NE(ugv_error("robot: {id: 2, goal: [0, -16], via: [[1, .nan]]}")
                .find("robot.via[0]: expected [x, y], two finite numbers"),
            std::string::npos);
  UavBoardConfig uav;
  std::string uav_error;
  EXPECT_FALSE(load_uav_config(write("uav_empty.yaml", "robot: {hal: sim}"), uav, uav_error));
  EXPECT_NE(uav_error.find("robot.id: required"), std::string::npos) << uav_error;
  // Everything else has its documented default.
  UgvBoardConfig c;
  std::string error;
  ASSERT_TRUE(
      load_ugv_config(write("minimal.yaml", "robot: {id: 4, goal: [6.0, -16.0]}"), c, error))
      << error;
  EXPECT_EQ(c.can_interface, "can0");
  EXPECT_EQ(c.nav.schedule.control.period, std::chrono::milliseconds(20));
  EXPECT_EQ(c.nav.odometry_timeout, std::chrono::milliseconds(60));
}

TEST_F(BoardConfig, ErrorsNameTheKeyAndTheProblem) {
  EXPECT_NE(ugv_error("can: {interface: [a, b]}").find("can.interface: expected a string"),
            std::string::npos);
  EXPECT_NE(ugv_error("robot: {id: 40}").find("robot.id: out of range [0, 31]"), std::string::npos);
  EXPECT_NE(ugv_error("wheels: {radius_m: fast}").find("wheels.radius_m: expected a number"),
            std::string::npos);
  EXPECT_NE(ugv_error("wheel: {radius_m: 0.1}").find("wheel: unknown key"), std::string::npos);
  EXPECT_NE(ugv_error("can: {intreface: can1}").find("can.intreface: unknown key"),
            std::string::npos);
  EXPECT_NE(ugv_error("robot: {goal: [1.0]}").find("robot.goal: expected a list of 2 numbers"),
            std::string::npos);
  EXPECT_NE(ugv_error("can: {counts_id: 0x800}").find("can.counts_id: out of range"),
            std::string::npos);
  EXPECT_NE(ugv_error("can: {speeds_id: 0x101}").find("must differ"), std::string::npos);
  EXPECT_NE(ugv_error("rates: {control_hz: 0}").find("rates.control_hz: out of range"),
            std::string::npos);
  EXPECT_NE(ugv_error("robot: {id: 1\n  goal: ]").find("line "), std::string::npos);
  EXPECT_NE(ugv_error("- 1\n- 2").find("(top level): expected a mapping"), std::string::npos);
  // Found by fuzz_yaml_config: these threw out of the reader instead of naming the problem.
  EXPECT_NE(ugv_error("rates:\n  control").find("rates: expected a mapping"), std::string::npos);
  EXPECT_NE(ugv_error("? [a, b]\n: 1").find("(top level): a key is not a name"), std::string::npos);
  // Found trying it as a new user: zero odometry noise (the estimate never grows uncertain),
  // a key given twice (YAML reads the first), a directory instead of a file (it aborted).
  EXPECT_NE(ugv_error("odometry: {sigma_v: 0}").find("odometry.sigma_v: out of range"),
            std::string::npos);
  EXPECT_NE(ugv_error("odometry: {sigma_omega: 0.0}").find("odometry.sigma_omega: out of range"),
            std::string::npos);
  EXPECT_NE(ugv_error("robot: {id: 1, goal: [0, -16]}\nrobot: {id: 2, goal: [2, -16]}")
                .find("robot: given twice"),
            std::string::npos);
  EXPECT_NE(ugv_error("robot: {id: 1, id: 3, goal: [0, -16]}").find("robot.id: given twice"),
            std::string::npos);
  UgvBoardConfig c;
  std::string error;
  EXPECT_FALSE(load_ugv_config((dir_ / "none.yaml").string(), c, error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
  EXPECT_FALSE(load_ugv_config(dir_.string(), c, error));
  EXPECT_NE(error.find("not a file"), std::string::npos) << error;
  UavBoardConfig uav;
  EXPECT_FALSE(load_uav_config(dir_.string(), uav, error));
  EXPECT_NE(error.find("not a file"), std::string::npos) << error;
}

TEST_F(BoardConfig, UavConfigWithCalibrationAndTags) {
  write("cam.yaml",
        "%YAML:1.0\nimage_width: 1280\nimage_height: 720\ncamera_matrix: !!opencv-matrix\n"
        "  rows: 3\n  cols: 3\n  dt: d\n  data: [900, 0, 640, 0, 900, 360, 0, 0, 1]\n");
  UavBoardConfig c;
  std::string error;
  ASSERT_TRUE(load_uav_config(write("uav.yaml", R"(
robot: {id: 0}
camera:
  device: /dev/video2
  calibration: cam.yaml
  tag_size_m: 0.2
  mount: downward
  mount_xyz: [0.1, 0.0, -0.05]
  tags:
    - {tag: 5, ugv: 1, height_m: 0.25}
    - {tag: 6, ugv: 2}
)"),
                              c, error))
      << error;
  EXPECT_EQ(c.camera.uri, "/dev/video2");
  EXPECT_EQ(c.rpe.camera.width, 1280);
  EXPECT_DOUBLE_EQ(c.rpe.camera.fx, 900.0);
  EXPECT_DOUBLE_EQ(c.rpe.tag_size_m, 0.2);
  ASSERT_EQ(c.rpe.tags.size(), 2u);
  EXPECT_EQ(c.rpe.tags[0].tag_id, 5);
  EXPECT_EQ(c.rpe.tags[1].ugv_id, 2);
  EXPECT_NEAR(c.rpe.tags[0].tag_in_body.p.z(), 0.25, 1e-12);
  // Its view: the cone inscribed in the calibrated image (720 px high, f = 900 px).
  EXPECT_NEAR(c.camera_view.half_angle_deg, std::atan(360.0 / 900.0) * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR(c.camera_view.tag_height_m, 0.5 * (0.25 + 0.3), 1e-12);  // the tags' mean
  // The downward camera looks along the UAV's -z.
  EXPECT_NEAR((c.rpe.camera_in_uav.q * Vec3::UnitZ() - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);

  EXPECT_FALSE(load_uav_config(write("u2.yaml", "camera: {device: x}"), c, error));
  EXPECT_NE(error.find("camera.calibration: required"), std::string::npos) << error;
  EXPECT_FALSE(load_uav_config(write("u3.yaml", "camera: {calibration: nothere.yaml}"), c, error));
  EXPECT_NE(error.find("camera.calibration:"), std::string::npos) << error;
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  EXPECT_FALSE(load_uav_config(
      write("u4.yaml", "camera: {calibration: cam.yaml, tags: [{tag: 700, ugv: 1}]}"), c, error));
  EXPECT_NE(error.find("camera.tags[0].tag: out of range"), std::string::npos) << error;
}

TEST_F(BoardConfig, UavConfigSetsItsFleetAndRefusesAnIdBeyondIt) {
  UavBoardConfig c;
  std::string error;
  ASSERT_TRUE(load_uav_config(write("uav_fleet.yaml", R"(
robot: {id: 2, hal: sim}
fleet: {separation_m: 3.0, peer_timeout_ms: 1500, peer_failsafe_ms: 2500}
)"),
                              c, error))
      << error;
  EXPECT_EQ(c.id, 2);
  EXPECT_DOUBLE_EQ(c.separation_m, 3.0);
  EXPECT_EQ(c.peer_timeout, std::chrono::milliseconds(1500));
  EXPECT_EQ(c.peer_failsafe, std::chrono::milliseconds(2500));
  ASSERT_TRUE(load_uav_config(write("uav_nofleet.yaml", "robot: {id: 0, hal: sim}"), c, error));
  EXPECT_DOUBLE_EQ(c.separation_m, 1.5);  // the default
  // The UGVs and the other UAVs would refuse every message of UAV 4.
  EXPECT_FALSE(load_uav_config(write("uav_id4.yaml", "robot: {id: 4, hal: sim}"), c, error));
  EXPECT_NE(error.find("robot.id: out of range"), std::string::npos) << error;
  EXPECT_FALSE(load_uav_config(
      write("uav_f1.yaml", "robot: {id: 0, hal: sim}\nfleet: {separation: 2}"), c, error));
  EXPECT_NE(error.find("fleet.separation: unknown key"), std::string::npos) << error;
  EXPECT_FALSE(load_uav_config(
      write("uav_f2.yaml", "robot: {id: 0, hal: sim}\nfleet: {separation_m: 0.1}"), c, error));
  EXPECT_NE(error.find("fleet.separation_m: out of range"), std::string::npos) << error;
}

TEST_F(BoardConfig, UavConfigDescribesItsLidarAndCameraView) {
  UavBoardConfig c;
  std::string error;
  // As colag_world --print-uav-sensors writes them for SITL.
  ASSERT_TRUE(load_uav_config(write("uav_sensors.yaml", R"(
robot: {id: 0, hal: sim}
lidar: {beams: 32, lowest_elevation_deg: -25.2, elevation_step_deg: 1.2, columns: 1200}
camera: {max_range_m: 5.0, fov_half_angle_deg: 75.0}
)"),
                              c, error))
      << error;
  EXPECT_EQ(c.lidar_pattern.beams, 32);
  EXPECT_DOUBLE_EQ(c.lidar_pattern.lowest_elevation_deg, -25.2);
  EXPECT_EQ(c.lidar_pattern.columns, 1200);
  EXPECT_DOUBLE_EQ(c.camera_view.range_m, 5.0);
  EXPECT_DOUBLE_EQ(c.camera_view.half_angle_deg, 75.0);
  EXPECT_DOUBLE_EQ(c.camera_view.tag_height_m, 0.3);  // no tags: the default height

  // Not described: nothing is inferred, the view is unknown (the altitude as configured).
  ASSERT_TRUE(load_uav_config(write("uav_plain.yaml", "robot: {id: 0, hal: sim}"), c, error));
  EXPECT_EQ(c.lidar_pattern.beams, 0);
  EXPECT_GE(c.camera_view.half_angle_deg, 90.0);

  EXPECT_FALSE(load_uav_config(
      write("uav_l1.yaml", "robot: {id: 0, hal: sim}\nlidar: {lowest_elevation_deg: -15}"), c,
      error));
  EXPECT_NE(error.find("lidar.beams: required"), std::string::npos) << error;
  EXPECT_FALSE(load_uav_config(
      write("uav_l2.yaml", "robot: {id: 0, hal: sim}\nlidar: {beams: 16, colums: 900}"), c, error));
  EXPECT_NE(error.find("lidar.colums: unknown key"), std::string::npos) << error;
  EXPECT_FALSE(load_uav_config(
      write("uav_c1.yaml", "robot: {id: 0, hal: sim}\ncamera: {fov_half_angle_deg: 200}"), c,
      error));
  EXPECT_NE(error.find("camera.fov_half_angle_deg: out of range"), std::string::npos) << error;
}

TEST_F(BoardConfig, UavOnPx4NamesItsReleaseTopicsAndFrames) {
  UavBoardConfig c;
  std::string error;
  ASSERT_TRUE(load_uav_config(write("uav_px4.yaml", R"(
robot: {id: 0, hal: px4}
px4: {release: "v1.15", dds_domain: 3, namespace: uav1, system_id: 2, origin: [1, 2, 0, 90]}
odometry: {source: px4, latency_ms: 15}
lidar: {topic: /cloud_registered_body, mount: [0, 0, -0.1, 0, 30, 0], max_range_m: 10}
camera: {device: sim}
)"),
                              c, error))
      << error;
  EXPECT_TRUE(c.px4_hal);
  EXPECT_TRUE(c.sim_camera);  // colag_world's camera (SITL): no calibration needed
  EXPECT_EQ(c.px4.release, hal::px4::Px4Release::kV115);
  EXPECT_EQ(c.px4.dds_domain, 3u);
  EXPECT_EQ(c.px4.ns, "uav1");
  EXPECT_EQ(c.px4.target_system, 2);
  EXPECT_NEAR((c.px4.origin.p - Vec3(1, 2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(yaw_of(c.px4.origin.q), M_PI / 2, 1e-12);
  EXPECT_TRUE(c.odometry_from_px4);
  EXPECT_EQ(c.px4.odometry_latency, std::chrono::milliseconds(15));
  EXPECT_EQ(c.lidar.dds_domain, 3u);  // the PX4 agent's domain unless said
  EXPECT_EQ(c.lidar.topic, "/cloud_registered_body");
  EXPECT_FLOAT_EQ(c.lidar.max_range_m, 10.0F);
  EXPECT_NEAR((c.lidar_mount.q * Vec3::UnitX()).z(), -0.5, 1e-12);  // pitched 30 deg down
  EXPECT_EQ(c.lidar_pattern.beams, 0);                              // no pattern: returns only

  auto refused = [&](const std::string& text, const char* why) {
    EXPECT_FALSE(load_uav_config(write("uav_bad.yaml", text), c, error)) << text;
    EXPECT_NE(error.find(why), std::string::npos) << error;
  };
  refused("robot: {id: 0, hal: px4}\ncamera: {device: sim}", "px4: required");
  refused("robot: {id: 0, hal: px4}\npx4: {dds_domain: 0}\ncamera: {device: sim}",
          "px4.release: required");
  refused("robot: {id: 0, hal: px4}\npx4: {release: main}\ncamera: {device: sim}",
          "px4.release: 'main' is not a known release (1.15, 1.16)");
  refused(
      "robot: {id: 0, hal: px4}\npx4: {release: '1.16'}\nodometry: {source: vins}\n"
      "camera: {device: sim}",
      "odometry.source: expected fast_lio");
  refused(
      "robot: {id: 0, hal: px4}\npx4: {release: '1.16', origin: [0, 0, 0]}\n"
      "camera: {device: sim}",
      "px4.origin: expected a list of 4 numbers");
  refused("robot: {id: 0, hal: drone}", "robot.hal: expected board, sim or px4");
}

}  // namespace
}  // namespace colag::board

namespace colag::board {
namespace {

// What the programs print about SCHED_FIFO and mlockall says what was asked for and granted.
TEST(RealtimeReport, SaysWhatWasRequestedAndWhatWasGranted) {
  platform::RealtimeSetup none;
  EXPECT_EQ(describe_realtime_setup(none),
            "SCHED_FIFO off (not requested), mlockall off (not requested)");
  platform::RealtimeSetup both;
  both.fifo_requested = both.memory_lock_requested = true;
  both.memory_lock = {Errc::kPermissionDenied, "refused (needs CAP_IPC_LOCK or RLIMIT_MEMLOCK)"};
  EXPECT_EQ(describe_realtime_setup(both),
            "SCHED_FIFO on, mlockall refused (needs CAP_IPC_LOCK or RLIMIT_MEMLOCK)");
}

}  // namespace
}  // namespace colag::board
