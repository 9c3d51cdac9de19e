#pragma once
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/sequence.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

enum class MapPatchEncoding : std::uint8_t {
  kPacked2Bit = 0,  // 2 bits per cell, row-major from (0,0), cell 0 in the low bits of byte 0
  kRunLength = 1,   // runs of one state (see common/map_patch_codec)
  kRowDelta = 2,    // runs over each cell XOR the cell one row below (see common/map_patch_codec)
};
template <>
struct EnumRange<MapPatchEncoding> {
  static constexpr MapPatchEncoding kLast = MapPatchEncoding::kRowDelta;
};

// A 2-D window of the UAV's map, classified for ground robots (UAV -> one UGV, ~5 Hz each).
// Cell (i, j) covers [origin_x_m + i*res, origin_x_m + (i+1)*res) x [origin_y_m + j*res, ...).
struct MapPatch {
  TimePoint stamp;
  RobotId uav_id = 0;
  RobotId ugv_id = 0;  // destination
  std::uint32_t seq = 0;
  double resolution_m = 0.0;
  double origin_x_m = 0.0;  // world coordinates of the corner of cell (0, 0)
  double origin_y_m = 0.0;
  std::uint16_t width_cells = 0;   // along x
  std::uint16_t height_cells = 0;  // along y
  MapPatchEncoding encoding = MapPatchEncoding::kPacked2Bit;
  Sequence<std::uint8_t, limits::kMaxPatchBytes>
      data;  // the encoded cells (common/map_patch_codec)
  friend bool operator==(const MapPatch&, const MapPatch&) = default;
};
COLAG_MESSAGE_FIELDS(MapPatch, stamp, uav_id, ugv_id, seq, resolution_m, origin_x_m, origin_y_m,
                     width_cells, height_cells, encoding, data);

// Every patch must arrive (a UGV plans on it): reliable. Filed under the UGV it is for.
template <>
inline constexpr TopicSpec<MapPatch> kTopicSpec<MapPatch> = {
    "colag_map_patch", &MapPatch::ugv_id, Reliability::kReliable, 4,
    Duration::zero(),  Delivery::kPerUgv};

}  // namespace colag::msg
