#include "colag/hal/ros2/point_cloud.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace colag::hal::ros2 {

namespace {

std::uint32_t swapped(std::uint32_t u) {
  return __builtin_bswap32(u);
}
std::uint64_t swapped(std::uint64_t u) {
  return __builtin_bswap64(u);
}

// A float or double stored at `p` (unaligned) in the cloud's byte order.
template <class T>
T read_as(const std::uint8_t* p, bool big_endian) {
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  U u;
  std::memcpy(&u, p, sizeof u);
  if (big_endian != (std::endian::native == std::endian::big)) u = swapped(u);
  return std::bit_cast<T>(u);
}

}  // namespace

Result<CloudLayout> cloud_layout(std::span<const PointFieldView> fields, std::uint32_t width,
                                 std::uint32_t height, std::uint32_t point_step,
                                 std::uint32_t row_step, bool big_endian, std::size_t data_size) {
  CloudLayout l;
  l.width = width;
  l.height = height;
  l.point_step = point_step;
  l.row_step = row_step;
  l.big_endian = big_endian;
  const char* names[3] = {"x", "y", "z"};
  bool found[3] = {false, false, false};
  for (const PointFieldView& f : fields) {
    for (int i = 0; i < 3; ++i) {
      if (f.name != names[i]) continue;
      if (f.datatype != kPointFieldFloat32 && f.datatype != kPointFieldFloat64)
        return Status{Errc::kInvalidArgument, "x, y and z must be FLOAT32 or FLOAT64"};
      if (f.count != 1)
        return Status{Errc::kInvalidArgument, "x, y or z with a count other than 1"};
      if (found[0] || found[1] || found[2]) {
        if (f.datatype != l.datatype)
          return Status{Errc::kInvalidArgument, "x, y and z of different datatypes"};
      }
      if (found[i]) return Status{Errc::kInvalidArgument, "a coordinate field twice"};
      found[i] = true;
      l.offset[i] = f.offset;
      l.datatype = f.datatype;
    }
  }
  if (!found[0] || !found[1] || !found[2])
    return Status{Errc::kInvalidArgument, "no x, y and z fields"};
  const std::uint64_t size = l.datatype == kPointFieldFloat64 ? 8 : 4;
  for (const std::uint32_t o : l.offset)
    if (std::uint64_t{o} + size > point_step)
      return Status{Errc::kInvalidArgument, "a coordinate lies outside point_step"};
  if (std::uint64_t{width} * point_step > row_step)
    return Status{Errc::kInvalidArgument, "row_step shorter than width * point_step"};
  if (std::uint64_t{row_step} * height > data_size)
    return Status{Errc::kInvalidArgument, "data shorter than row_step * height"};
  return l;
}

CloudStats extract_returns(const CloudLayout& l, std::span<const std::uint8_t> data,
                           float min_range_m, float max_range_m, std::span<LidarPoint> out) {
  CloudStats st;
  st.points = std::size_t{l.width} * l.height;
  if (st.points == 0 || out.empty() ||
      std::uint64_t{l.row_step} * l.height > data.size()) {  // cloud_layout checked; once more
    return st;
  }
  // Evenly thinned: every k-th point, k the smallest that fits (a Mid-360 frame is ~20 000
  // points; the mapper's budget is sized for a fixed count).
  const std::size_t stride = (st.points + out.size() - 1) / out.size();
  const bool f64 = l.datatype == kPointFieldFloat64;
  const float min2 = min_range_m * min_range_m, max2 = max_range_m * max_range_m;
  std::size_t index = 0;
  for (std::uint32_t r = 0; r < l.height; ++r) {
    const std::uint8_t* row = data.data() + std::size_t{r} * l.row_step;
    for (std::uint32_t c = 0; c < l.width; ++c, ++index) {
      if (index % stride != 0) {
        ++st.thinned;
        continue;
      }
      const std::uint8_t* p = row + std::size_t{c} * l.point_step;
      float v[3];
      for (int i = 0; i < 3; ++i) {
        v[i] = f64 ? static_cast<float>(read_as<double>(p + l.offset[i], l.big_endian))
                   : read_as<float>(p + l.offset[i], l.big_endian);
      }
      const float d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      if (!std::isfinite(d2) || d2 < min2) {
        ++st.invalid;
        continue;
      }
      if (d2 > max2) {
        ++st.too_far;
        continue;
      }
      if (st.kept == out.size()) {
        ++st.thinned;
        continue;
      }
      out[st.kept++] = {v[0], v[1], v[2]};
    }
  }
  return st;
}

}  // namespace colag::hal::ros2
