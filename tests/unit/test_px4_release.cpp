// The PX4 releases the driver speaks: names in the configuration, topic names on the wire.
#include "colag/hal/px4/px4_release.hpp"

#include "colag/hal/ros2/ros2_names.hpp"

#include <gtest/gtest.h>

using namespace colag::hal::px4;

TEST(Px4Release, ParsesTheKnownReleasesAndRefusesOthersByName) {
  EXPECT_EQ(parse_px4_release("1.15").value(), Px4Release::kV115);
  EXPECT_EQ(parse_px4_release("v1.16").value(), Px4Release::kV116);
  for (const char* bad : {"", "1.14", "1.17", "main", "1.16.0x"}) {
    const auto r = parse_px4_release(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_NE(std::string(r.status().message()).find("1.15, 1.16"), std::string::npos);
  }
}

TEST(Px4Release, TopicNamesFollowTheReleaseAndTheNamespace) {
  EXPECT_EQ(px4_dds_topic(Px4Release::kV115, Px4Topic::kVehicleStatus, ""),
            "rt/fmu/out/vehicle_status");
  EXPECT_EQ(px4_dds_topic(Px4Release::kV116, Px4Topic::kVehicleStatus, ""),
            "rt/fmu/out/vehicle_status_v1");
  EXPECT_EQ(px4_dds_topic(Px4Release::kV116, Px4Topic::kTrajectorySetpoint, "/px4_1/"),
            "rt/px4_1/fmu/in/trajectory_setpoint");
  EXPECT_EQ(px4_dds_topic(Px4Release::kV115, Px4Topic::kOffboardControlMode, "uav"),
            "rt/uav/fmu/in/offboard_control_mode");
  // On the bus, the other release's status topic names its release.
  EXPECT_EQ(release_of_status_topic("rt/fmu/out/vehicle_status_v1", "").value(), Px4Release::kV116);
  EXPECT_EQ(release_of_status_topic("rt/uav/fmu/out/vehicle_status", "uav").value(),
            Px4Release::kV115);
  EXPECT_FALSE(release_of_status_topic("rt/fmu/out/vehicle_odometry", ""));
}

TEST(Ros2Names, TopicsTakeTheRtPrefixAndTheirNamespace) {
  using colag::hal::ros2::ros2_dds_topic;
  EXPECT_EQ(ros2_dds_topic("/Odometry"), "rt/Odometry");
  EXPECT_EQ(ros2_dds_topic("livox/lidar"), "rt/livox/lidar");
  EXPECT_EQ(ros2_dds_topic("/uav1/", "/fmu/in/x"), "rt/uav1/fmu/in/x");
  EXPECT_EQ(ros2_dds_topic("", "fmu/out/y"), "rt/fmu/out/y");
}
