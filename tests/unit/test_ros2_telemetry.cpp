// The ROS 2 telemetry messages, their CDR bytes and schemas, and the MCAP writer's refusals.
// (The files themselves are checked by the reference reader: tests/mcap, label mcap.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "allocation_counter.hpp"
#include "colag/hal/ros2/cdr.hpp"
#include "colag/hal/ros2/ros2_messages.hpp"
#include "colag/hal/ros2/ros2_schemas.hpp"
#include "colag/sim/mcap/mcap_writer.hpp"

namespace colag {
namespace {

using namespace hal::ros2;  // NOLINT(google-build-using-namespace)

TEST(Ros2Schemas, CarryEachDependencyOnceAfterTheType) {
  const std::string s = ros2msg_schema("nav_msgs/msg/Odometry");
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.rfind("std_msgs/Header header\n", 0), 0U);  // the type's own text first
  for (const char* dep : {"MSG: std_msgs/Header\n", "MSG: builtin_interfaces/Time\n",
                          "MSG: geometry_msgs/Pose\n", "MSG: geometry_msgs/Twist\n"}) {
    const std::size_t at = s.find(dep);
    ASSERT_NE(at, std::string::npos) << dep;
    EXPECT_EQ(s.find(dep, at + 1), std::string::npos) << dep << " twice";
  }
  EXPECT_TRUE(ros2msg_schema("nav_msgs/msg/NoSuchType").empty());
  EXPECT_TRUE(ros2msg_schema("nav_msgs/Odometry").empty());  // not a ROS 2 type name
}

// The ROS 2 package shipped for users (ros2/colag_msgs) declares the types the firmware sends
// and the MCAP files carry: its .msg files, comments and blank lines dropped, are the schemas.
TEST(Ros2Schemas, TheShippedColagMsgsPackageDeclaresTheSameTypes) {
  for (const char* type : {"UgvStatus", "UavStatus", "UgvCommand"}) {
    std::ifstream in(std::string(COLAG_ROS2_MSGS_DIR) + "/" + type + ".msg");
    ASSERT_TRUE(in) << type;
    std::string line, text;
    while (std::getline(in, line)) {
      line = line.substr(0, line.find('#'));
      line = line.substr(0, line.find_last_not_of(' ') + 1);
      if (!line.empty()) text += line + "\n";
    }
    const std::string schema = ros2msg_schema(std::string("colag_msgs/msg/") + type);
    EXPECT_EQ(text, schema.substr(0, schema.find("====="))) << type;
  }
}

TEST(Ros2Messages, UgvOdometryCarriesPoseCovarianceAndFrames) {
  msg::UgvStatus s;
  s.stamp = TimePoint{std::chrono::milliseconds(12'345)};
  s.position_m[0] = 1.5;
  s.position_m[1] = -2.0;
  s.yaw_rad = M_PI / 2;
  s.covariance[0] = 0.01;  // x
  s.covariance[4] = 0.02;  // y
  s.covariance[8] = 0.03;  // yaw
  s.covariance[2] = s.covariance[6] = 0.005;
  OdometryMessage m("ugv0/base_link");
  m.set(s);
  const auto& o = m.sample();
  EXPECT_STREQ(o.header.frame_id, "map");
  EXPECT_STREQ(o.child_frame_id, "ugv0/base_link");
  EXPECT_EQ(o.header.stamp.sec, 12);
  EXPECT_EQ(o.header.stamp.nanosec, 345'000'000U);
  EXPECT_NEAR(o.pose.pose.orientation.z, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(o.pose.pose.orientation.w, std::sqrt(0.5), 1e-12);
  // (x, y, yaw) land on (x, y, rz) of the 6x6.
  EXPECT_EQ(o.pose.covariance[0], 0.01);
  EXPECT_EQ(o.pose.covariance[7], 0.02);
  EXPECT_EQ(o.pose.covariance[35], 0.03);
  EXPECT_EQ(o.pose.covariance[5], 0.005);
  EXPECT_EQ(o.pose.covariance[30], 0.005);
}

TEST(Ros2Messages, CapacitiesRefuseRatherThanGrow) {
  TfMessage tf(2);
  const double q[4] = {1, 0, 0, 0};
  EXPECT_TRUE(tf.add(TimePoint{}, "a", 0, 0, 0, q));
  EXPECT_TRUE(tf.add(TimePoint{}, "b", 0, 0, 0, q));
  EXPECT_FALSE(tf.add(TimePoint{}, "c", 0, 0, 0, q));
  EXPECT_EQ(tf.sample().transforms._length, 2U);
  MarkerArrayMessage markers(1, 2);
  const double at[4] = {}, scale[3] = {1, 1, 1};
  ASSERT_NE(markers.add("x", 0, MarkerArrayMessage::kLineStrip, {1, 1, 1, 1}, at, scale), nullptr);
  EXPECT_TRUE(markers.add_point(0, 0, 0));
  EXPECT_TRUE(markers.add_point(1, 0, 0));
  EXPECT_FALSE(markers.add_point(2, 0, 0));
  EXPECT_EQ(markers.add("x", 1, MarkerArrayMessage::kCube, {1, 1, 1, 1}, at, scale), nullptr);
  PathMessage path(1);
  path.clear(TimePoint{});
  EXPECT_TRUE(path.push(0, 0, 0, 0));
  EXPECT_FALSE(path.push(1, 0, 0, 0));
}

// The boards refill these every period: within capacity, nothing is allocated.
TEST(Ros2Messages, RefillingAllocatesNothing) {
  PathMessage path(64);
  GridMessage grid(GridGeometry2d(0, 0, 0.1, 50, 40));
  MarkerArrayMessage markers(8, 8);
  test::AllocationCounter count;
  for (int k = 0; k < 3; ++k) {
    path.clear(TimePoint{});
    for (int i = 0; i < 64; ++i)
      (void)path.push(i, 0, 0, 0);
    grid.fill(TimePoint{}, [](CellIndex c) -> std::int8_t { return c.x > c.y ? 100 : 0; });
    markers.clear(TimePoint{});
    (void)markers.delete_all();
    const double at[4] = {}, scale[3] = {1, 1, 1};
    (void)markers.add("m", k, MarkerArrayMessage::kText, {1, 1, 1, 1}, at, scale);
    markers.set_text("label");
  }
  EXPECT_EQ(count.count(), 0U);
  EXPECT_EQ(grid.sample().data._length, 50U * 40U);
  EXPECT_EQ(grid.sample().info.width, 50U);
}

TEST(Ros2Cdr, StartsWithTheLittleEndianEncapsulation) {
  PathMessage path(4);
  path.clear(TimePoint{std::chrono::seconds(3)});
  (void)path.push(1, 2, 0, 0);
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(to_cdr(&path.sample(), nav_msgs_msg_dds__Path__desc, bytes));
  ASSERT_GE(bytes.size(), 8U);
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[1], 0x01);
  EXPECT_EQ(bytes[4], 3);  // header.stamp.sec, little endian
  // header (8 + 4 + "map\0" = 16), poses count (4), then one PoseStamped (8 + 4 + 4 + pad 4
  // + 56) = 4 + 16 + 4 + 76.
  EXPECT_EQ(bytes.size(), 4U + 16U + 4U + 76U);
}

TEST(McapWriter, RefusesWhatItCannotWrite) {
  mcap::McapWriter w;
  EXPECT_FALSE(w.open("/nonexistent-folder/x.mcap"));
  EXPECT_NE(w.error().find("/nonexistent-folder/x.mcap"), std::string::npos);
  EXPECT_EQ(w.add_schema("a/msg/B", "ros2msg", ""), 0);  // not open
  const std::string path = ::testing::TempDir() + "colag_mcap_writer_test.mcap";
  ASSERT_TRUE(w.open(path));
  const std::uint16_t schema = w.add_schema("std_msgs/msg/Empty", "ros2msg", "");
  const std::uint16_t channel = w.add_channel(schema, "/x", "cdr");
  EXPECT_EQ(w.add_channel(99, "/y", "cdr"), 0);  // no such schema
  const std::uint8_t data[4] = {0, 1, 0, 0};
  EXPECT_TRUE(w.write(channel, 1, 1, data));
  EXPECT_FALSE(w.write(channel + 1, 1, 1, data));  // no such channel
  EXPECT_TRUE(w.close());
  EXPECT_TRUE(w.close());  // idempotent
  EXPECT_FALSE(w.write(channel, 2, 2, data));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  unsigned char magic[8];
  ASSERT_EQ(std::fread(magic, 1, 8, f), 8U);
  ASSERT_EQ(std::fseek(f, -8, SEEK_END), 0);
  unsigned char tail[8];
  ASSERT_EQ(std::fread(tail, 1, 8, f), 8U);
  std::fclose(f);
  EXPECT_EQ(std::string(reinterpret_cast<char*>(magic) + 1, 4), "MCAP");
  EXPECT_EQ(std::string(reinterpret_cast<char*>(tail), 8),
            std::string(reinterpret_cast<char*>(magic), 8));
  std::remove(path.c_str());
}

}  // namespace
}  // namespace colag
