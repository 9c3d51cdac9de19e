#pragma once
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::msg {

enum class MapPatchEncoding : std::uint8_t {
  kPacked2Bit = 0,  // 2 bits per cell, row-major from (0,0), cell 0 in the low bits of byte 0
  kRunLength = 1,   // runs of one state (see common/map_patch_codec)
  kRowDelta = 2,    // runs over each cell XOR the cell one row below (see common/map_patch_codec)
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
  std::uint16_t data_bytes = 0;  // used bytes of data[]
  std::uint8_t data[limits::kMaxPatchBytes] = {};
  friend bool operator==(const MapPatch&, const MapPatch&) = default;
};

}  // namespace colag::msg
