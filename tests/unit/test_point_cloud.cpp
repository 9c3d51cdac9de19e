// PointCloud2 -> returns: the layout read from the message, malformed clouds refused, the
// Livox driver's "no return" points and far points skipped, thinning to the capacity.
#include "colag/hal/ros2/point_cloud.hpp"

#include "colag/common/geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace colag;
using namespace colag::hal::ros2;

namespace {

// A cloud of `pts` in livox_ros_driver2's xfer_format 0 layout (26 bytes a point), or with
// float64 coordinates behind a 4-byte field, in either byte order.
struct Cloud {
  std::vector<PointFieldView> fields;
  std::vector<std::uint8_t> data;
  std::uint32_t step = 0;
  bool big = false;
};

template <class T>
void put(std::uint8_t* p, T v, bool big) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof v);
  if (big) std::reverse(b, b + sizeof b);
  std::memcpy(p, b, sizeof b);
}

Cloud livox(const std::vector<Vec3>& pts) {
  Cloud c;
  c.fields = {{"x", 0, 7, 1},          {"y", 4, 7, 1},    {"z", 8, 7, 1},
              {"intensity", 12, 7, 1}, {"tag", 16, 2, 1}, {"line", 17, 2, 1},
              {"timestamp", 18, 8, 1}};
  c.step = 26;
  c.data.assign(pts.size() * c.step, 0);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      put(c.data.data() + i * c.step + 4 * k, static_cast<float>(pts[i][k]), false);
  return c;
}

Cloud doubles(const std::vector<Vec3>& pts, bool big) {
  Cloud c;
  c.fields = {{"ring", 0, 4, 1}, {"z", 20, 8, 1}, {"y", 12, 8, 1}, {"x", 4, 8, 1}};  // any order
  c.step = 28;
  c.big = big;
  c.data.assign(pts.size() * c.step, 0);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    put(c.data.data() + i * c.step + 4, pts[i].x(), big);
    put(c.data.data() + i * c.step + 12, pts[i].y(), big);
    put(c.data.data() + i * c.step + 20, pts[i].z(), big);
  }
  return c;
}

CloudStats read(const Cloud& c, std::vector<hal::LidarPoint>& out, std::size_t cap = 100) {
  const auto n = static_cast<std::uint32_t>(c.data.size() / c.step);
  const Result<CloudLayout> l =
      cloud_layout(c.fields, n, 1, c.step, n * c.step, c.big, c.data.size());
  EXPECT_TRUE(l) << l.status().message();
  out.assign(cap, {});
  return l ? extract_returns(l.value(), c.data, 0.3F, 8.0F, out) : CloudStats{};
}

}  // namespace

TEST(PointCloud, ReadsTheLivoxLayoutAndSkipsNoReturnsNaNsAndFarPoints) {
  const float nan = std::nanf("");
  std::vector<hal::LidarPoint> out;
  const CloudStats st =
      read(livox({{1, 2, 3}, {0, 0, 0}, {nan, 0, 0}, {20, 0, 0}, {-4, 0.5, -1}}), out);
  EXPECT_EQ(st.points, 5u);
  EXPECT_EQ(st.kept, 2u);
  EXPECT_EQ(st.invalid, 2u);  // Livox's (0, 0, 0) "no return", and the NaN
  EXPECT_EQ(st.too_far, 1u);
  EXPECT_FLOAT_EQ(out[0].x_m, 1.0F);
  EXPECT_FLOAT_EQ(out[1].z_m, -1.0F);
}

TEST(PointCloud, ReadsFloat64FieldsInAnyOrderAndEitherByteOrder) {
  for (const bool big : {false, true}) {
    std::vector<hal::LidarPoint> out;
    const CloudStats st = read(doubles({{1.5, -2, 0.25}, {3, 4, 1}}, big), out);
    ASSERT_EQ(st.kept, 2u) << big;
    EXPECT_FLOAT_EQ(out[0].x_m, 1.5F);
    EXPECT_FLOAT_EQ(out[0].y_m, -2.0F);
    EXPECT_FLOAT_EQ(out[1].z_m, 1.0F);
  }
}

TEST(PointCloud, ThinsEvenlyToItsCapacity) {
  std::vector<Vec3> pts;
  pts.reserve(1000);
  for (int i = 0; i < 1000; ++i)
    pts.emplace_back(1.0 + 0.005 * i, 0.0, 0.0);
  std::vector<hal::LidarPoint> out;
  const CloudStats st = read(livox(pts), out, 300);
  EXPECT_LE(st.kept, 300u);
  EXPECT_GE(st.kept, 250u);  // every 4th: 250
  EXPECT_EQ(st.kept + st.thinned, 1000u);
  EXPECT_GT(out[st.kept - 1].x_m, 5.5F);  // spread over the whole cloud, not its start
}

TEST(PointCloud, RefusesMalformedLayoutsWithTheReason) {
  const Cloud c = livox({{1, 2, 3}});
  auto refuse = [&](std::vector<PointFieldView> fields, std::uint32_t step, std::uint32_t row,
                    std::size_t size, const char* why) {
    const auto l = cloud_layout(fields, 1, 1, step, row, false, size);
    ASSERT_FALSE(l) << why;
    EXPECT_NE(std::string(l.status().message()).find(why), std::string::npos)
        << l.status().message();
  };
  refuse({{"x", 0, 7, 1}, {"y", 4, 7, 1}}, 26, 26, 26, "no x, y and z");
  refuse({{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 2, 1}}, 26, 26, 26, "FLOAT32 or FLOAT64");
  refuse({{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 24, 7, 1}}, 26, 26, 26, "outside point_step");
  refuse(c.fields, 26, 20, 26, "row_step shorter");
  refuse(c.fields, 26, 26, 10, "data shorter");
  refuse({{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 3}}, 26, 26, 26, "count");
}
