#pragma once
// Map sharing (paper Sec. III-B): for each UGV, a 2-D window of the UAV's 3-D map around it,
// classified for a ground robot and sent as a compact MapPatch.
// - Window: the UGV's position +- half_box_m, shifted ahead along its heading (4.375 m ahead,
//   0.625 m behind by default) while it moves faster than moving_speed_mps.
// - A ground cell is occupied if any voxel of the robot's body band [band_low_m, band_high_m)
//   above it is occupied; free if none is and the ground voxel or the lowest band voxel has
//   been observed (any obstacle standing there tall enough to matter fills that lowest band
//   voxel, so seeing it free rules the obstacle out); unknown otherwise (occlusion shadows,
//   the blind cone under the UAV). Requiring every band voxel to be observed instead leaves
//   rings of unknown between the LiDAR's beam rings that no obstacle explains.
// - Rate: every UGV has its own period (default 200 ms = 5 Hz) and its own due time, so no UGV
//   waits for another; a patch identical to the last one sent to that UGV is skipped unless
//   `refresh` has passed.
#include <array>
#include <cstdint>

#include "colag/common/map_patch_codec.hpp"
#include "colag/msg/map_patch.hpp"
#include "colag/uav/mapper.hpp"

namespace colag::uav {

struct SharerConfig {
  double half_box_m = 2.5;
  double shift_ahead_m = 1.875;  // window centre moved ahead: 4.375 m ahead, 0.625 m behind
  double moving_speed_mps = 0.2;
  double band_low_m = 0.1;  // above the ground voxel layer
  double band_high_m = 0.7;
  Duration period = std::chrono::milliseconds(200);
  Duration refresh = std::chrono::seconds(2);
};

struct SharerCounters {
  std::uint64_t patches = 0;
  std::uint64_t skipped_unchanged = 0;
  std::uint64_t bytes = 0;  // payload bytes sent
};

class MapSharer {
 public:
  explicit MapSharer(const SharerConfig& config = {}) : config_(config) {}

  // Cuts and encodes the patch for a UGV at `position` with heading `yaw_rad` and speed.
  // Returns false if the window lies outside the map. Fills everything but stamp and ids.
  bool make_patch(const Mapper& map, const Vec2& position, double yaw_rad, double speed_mps,
                  msg::MapPatch& out);
  // The per-UGV rate and change filter: true when `patch` (already cut) should be sent now to
  // UGV `ugv_id`; then it is remembered as that UGV's last patch.
  bool due(RobotId ugv_id, TimePoint now) const;
  bool should_send(RobotId ugv_id, TimePoint now, const msg::MapPatch& patch);

  CellState classify(const Mapper& map, int x, int y) const;
  const SharerCounters& counters() const { return counters_; }
  const SharerConfig& config() const { return config_; }

 private:
  struct PerUgv {
    TimePoint next_due{};
    TimePoint last_sent = kNever;
    double origin_x_m = 0.0, origin_y_m = 0.0;
    std::uint16_t width = 0, height = 0, bytes = 0;
    std::uint32_t checksum = 0;
  };
  // The voxel layers of the robot's body band: [z0, z1), z0 at least 1 (layer z0 - 1 is the
  // ground's). One computation for make_patch and classify.
  struct Band {
    int z0, z1;
  };
  Band band(const GridGeometry3d& g) const;

  SharerConfig config_;
  SharerCounters counters_;
  PatchCells cells_;
  // Per ground cell of the patch, rows kMaxPatchSideCells apart: 0 or 1.
  std::array<std::uint8_t, limits::kMaxPatchCells> occupied_{}, seen_low_{};
  std::array<PerUgv, limits::kMaxUgvs> ugvs_{};
};

// What the original implementation would send for the same window: the int32 addresses of
// every occupied and unknown voxel of the 3-D box (5 x 5 x 1.4 m around the UGV, the part
// inside the grid), plus its fixed header. For the bandwidth comparison only.
std::size_t original_patch_bytes(const Mapper& map, const msg::MapPatch& patch, double z_low_m,
                                 double z_high_m);

}  // namespace colag::uav
