#pragma once
// sensor_msgs/PointCloud2 -> LiDAR returns, reading the field layout from the message (never
// assumed: livox_ros_driver2 with xfer_format 0 sends x y z intensity tag line timestamp,
// FAST-LIO's clouds x y z intensity normal_x ... curvature). Pure code: the DDS driver hands it
// the message's fields and bytes. Malformed clouds are refused with the reason; points that are
// not finite, at the origin (Livox's "no return") or beyond the range are skipped and counted.
#include <cstdint>
#include <span>
#include <string_view>

#include "colag/common/status.hpp"
#include "colag/hal/lidar.hpp"

namespace colag::hal::ros2 {

// sensor_msgs/PointField datatypes.
inline constexpr std::uint8_t kPointFieldFloat32 = 7;
inline constexpr std::uint8_t kPointFieldFloat64 = 8;

struct PointFieldView {
  std::string_view name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;
};

// Where x, y and z sit in each point, and how the points are laid out.
struct CloudLayout {
  std::uint32_t offset[3] = {};
  std::uint8_t datatype = kPointFieldFloat32;  // of all three
  std::uint32_t point_step = 0;
  std::uint32_t row_step = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool big_endian = false;
};

// Checks the header of a cloud whose data holds `data_size` bytes.
Result<CloudLayout> cloud_layout(std::span<const PointFieldView> fields, std::uint32_t width,
                                 std::uint32_t height, std::uint32_t point_step,
                                 std::uint32_t row_step, bool big_endian, std::size_t data_size);

struct CloudStats {
  std::size_t points = 0;   // in the message
  std::size_t kept = 0;     // written to `out`
  std::size_t invalid = 0;  // not finite, or at the origin
  std::size_t too_far = 0;  // beyond max_range_m
  std::size_t thinned = 0;  // dropped to fit `out` (every k-th point kept)
};

// The returns of the cloud, in its own frame, into `out` (evenly thinned when there are more
// than `out` holds). Points nearer than min_range_m count as invalid (the sensor's own body).
CloudStats extract_returns(const CloudLayout& layout, std::span<const std::uint8_t> data,
                           float min_range_m, float max_range_m, std::span<LidarPoint> out);

}  // namespace colag::hal::ros2
