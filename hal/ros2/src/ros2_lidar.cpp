#include <array>

#include "colag/common/limits.hpp"
#include "colag/hal/dds/take_one.hpp"
#include "colag/hal/ros2/ros2_devices.hpp"
#include "ros2_msgs.h"

namespace colag::hal::ros2 {

bool Ros2Lidar::init(const Ros2LidarConfig& config, std::string& error) {
  config_ = config;
  points_.resize(limits::kMaxLidarPoints);
  if (!dds_.init(config.dds_domain)) {
    error = "LiDAR on DDS domain " + std::to_string(config.dds_domain) + ": " + dds_.last_error();
    return false;
  }
  reader_ = dds_.reader(ros2_dds_topic(config.topic), sensor_msgs_msg_dds__PointCloud2__desc, 2);
  if (!reader_) {
    error = "LiDAR: " + dds_.last_error();
    return false;
  }
  return true;
}

bool Ros2Lidar::poll(LidarScanView& out) {
  // The newest cloud only: an older one queued behind it is superseded.
  bool got = false;
  std::size_t kept = 0;
  TimePoint stamp{};
  while (dds::take_one<sensor_msgs_msg_dds__PointCloud2_>(reader_, [&](const auto& m) {
    ++counters_.clouds;
    std::array<PointFieldView, 16> fields;
    const std::size_t n = std::min<std::size_t>(m.fields._length, fields.size());
    for (std::size_t i = 0; i < n; ++i) {
      const auto& f = m.fields._buffer[i];
      fields[i] = {f.name != nullptr ? f.name : "", f.offset, f.datatype, f.count};
    }
    const Result<CloudLayout> layout =
        cloud_layout(std::span(fields.data(), n), m.width, m.height, m.point_step, m.row_step,
                     m.is_bigendian, m.data._length);
    if (!layout) {
      ++counters_.malformed;
      refusal_ = layout.status().message();
      return;
    }
    const CloudStats st = extract_returns(layout.value(), std::span(m.data._buffer, m.data._length),
                                          config_.min_range_m, config_.max_range_m, points_);
    counters_.points += st.points;
    counters_.kept += st.kept;
    counters_.thinned += st.thinned;
    kept = st.kept;
    stamp = clock_.now() - config_.latency;
    got = true;
  })) {
  }
  if (!got) return false;
  out = LidarScanView{};
  out.stamp = stamp;
  out.max_range_m = config_.max_range_m;
  out.points = std::span<const LidarPoint>(points_.data(), kept);
  return true;
}

}  // namespace colag::hal::ros2
