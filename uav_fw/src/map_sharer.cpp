#include "colag/uav/map_sharer.hpp"

#include <algorithm>
#include <cmath>

namespace colag::uav {

namespace {
// One row of a band layer into the per-cell flags (0 or 1; bytes, not bool, which GCC does not
// vectorise). The flags and the map row are both char types, which may alias anything: without
// `__restrict` (GCC's and Clang's) the compiler would need a run-time overlap check and keeps
// these loops scalar.
void mark_if_not(std::uint8_t* __restrict mark, const std::int8_t* __restrict row, int n,
                 std::int8_t value) {
  for (int x = 0; x < n; ++x)
    mark[x] |= static_cast<std::uint8_t>(row[x] != value);
}
void mark_if_at_least(std::uint8_t* __restrict mark, const std::int8_t* __restrict row, int n,
                      std::int8_t value) {
  for (int x = 0; x < n; ++x)
    mark[x] |= static_cast<std::uint8_t>(row[x] >= value);
}

// FNV-1a over the payload: detects an unchanged patch without keeping a copy of it.
std::uint32_t checksum(const msg::MapPatch& p) {
  std::uint32_t h = 2166136261U;
  for (std::size_t i = 0; i < p.data.count; ++i)
    h = (h ^ p.data.items[i]) * 16777619U;
  return h;
}
}  // namespace

MapSharer::Band MapSharer::band(const GridGeometry3d& g) const {
  return {
      std::max(1, static_cast<int>(
                      std::floor((config_.band_low_m - g.origin_z()) / g.resolution() + 1e-9))),
      std::min(g.cells_z(), static_cast<int>(std::ceil(
                                (config_.band_high_m - g.origin_z()) / g.resolution() - 1e-9)))};
}

CellState MapSharer::classify(const Mapper& map, int x, int y) const {
  const auto [z0, z1] = band(map.geometry());
  for (int z = z0; z < z1; ++z) {
    if (map.state(VoxelIndex{x, y, z}) == VoxelState::kOccupied) return CellState::kOccupied;
  }
  const bool seen_low =
      map.observed(VoxelIndex{x, y, z0 - 1}) || map.observed(VoxelIndex{x, y, z0});
  return seen_low ? CellState::kFree : CellState::kUnknown;
}

bool MapSharer::make_patch(const Mapper& map, const Vec2& position, double yaw, double speed,
                           msg::MapPatch& out) {
  if (!all_finite(position) || !std::isfinite(yaw)) return false;
  const GridGeometry2d g = map.geometry().layer();
  Vec2 centre = position;
  if (std::abs(speed) > config_.moving_speed_mps) {
    centre += config_.shift_ahead_m * Vec2(std::cos(yaw), std::sin(yaw));
  }
  const Vec2 half = Vec2::Constant(config_.half_box_m);
  CellIndex lo = g.cell_of(centre - half), hi = g.cell_of(centre + half);
  lo.x = std::max(lo.x, 0);
  lo.y = std::max(lo.y, 0);
  hi.x = std::min({hi.x, g.cells_x() - 1, lo.x + limits::kMaxPatchSideCells - 1});
  hi.y = std::min({hi.y, g.cells_y() - 1, lo.y + limits::kMaxPatchSideCells - 1});
  if (hi.x < lo.x || hi.y < lo.y) return false;
  cells_.width = hi.x - lo.x + 1;
  cells_.height = hi.y - lo.y + 1;
  // Layer by layer over contiguous rows (cache friendly), accumulating per ground cell:
  // any band voxel occupied / the ground or the lowest band voxel observed.
  const auto& g3 = map.geometry();
  const auto [z0, z1] = band(g3);
  // Branch-free inner loops on the raw log-odds, which the compiler vectorises when their length
  // is a constant: away from the grid's east edge each row is read kMaxPatchSideCells wide (the
  // flags beyond the patch are never used). A sharing step reads ~17 000 voxels per UGV.
  constexpr int kSide = limits::kMaxPatchSideCells;
  const bool whole_rows = lo.x + kSide <= g3.cells_x();
  const std::size_t n = std::size_t{kSide} * static_cast<std::size_t>(cells_.height);
  std::fill_n(occupied_.begin(), n, 0);
  std::fill_n(seen_low_.begin(), n, 0);
  const std::int8_t unknown = map.raw_unknown(), occupied = map.raw_occupied();
  for (int z = z0 - 1; z < z1; ++z) {
    for (int y = 0; y < cells_.height; ++y) {
      const std::int8_t* row = map.row(lo.y + y, z) + lo.x;
      std::uint8_t* seen = &seen_low_[static_cast<std::size_t>(y) * kSide];
      std::uint8_t* occ = &occupied_[static_cast<std::size_t>(y) * kSide];
      if (z <= z0) {
        if (whole_rows) {
          mark_if_not(seen, row, kSide, unknown);
        } else {
          mark_if_not(seen, row, cells_.width, unknown);
        }
      }
      if (z >= z0) {
        if (whole_rows) {
          mark_if_at_least(occ, row, kSide, occupied);
        } else {
          mark_if_at_least(occ, row, cells_.width, occupied);
        }
      }
    }
  }
  for (int y = 0; y < cells_.height; ++y) {
    for (int x = 0; x < cells_.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * kSide + x;
      cells_.cells[static_cast<std::size_t>(y) * cells_.width + x] =
          occupied_[i] != 0 ? CellState::kOccupied
                            : (seen_low_[i] != 0 ? CellState::kFree : CellState::kUnknown);
    }
  }
  if (!encode_patch(cells_, out)) return false;
  out.resolution_m = g.resolution();
  out.origin_x_m = g.origin_x() + lo.x * g.resolution();
  out.origin_y_m = g.origin_y() + lo.y * g.resolution();
  return true;
}

bool MapSharer::due(RobotId ugv_id, TimePoint now) const {
  return ugv_id < limits::kMaxUgvs && now >= ugvs_[ugv_id].next_due;
}

bool MapSharer::should_send(RobotId ugv_id, TimePoint now, const msg::MapPatch& patch) {
  if (!due(ugv_id, now)) return false;
  PerUgv& u = ugvs_[ugv_id];
  u.next_due = now + config_.period;
  const std::uint32_t sum = checksum(patch);
  const bool same = u.origin_x_m == patch.origin_x_m && u.origin_y_m == patch.origin_y_m &&
                    u.width == patch.width_cells && u.height == patch.height_cells &&
                    u.bytes == patch.data.count && u.checksum == sum;
  if (same && !elapsed(now, u.last_sent, config_.refresh)) {
    ++counters_.skipped_unchanged;
    return false;
  }
  u.origin_x_m = patch.origin_x_m;
  u.origin_y_m = patch.origin_y_m;
  u.width = patch.width_cells;
  u.height = patch.height_cells;
  u.bytes = patch.data.count;
  u.checksum = sum;
  u.last_sent = now;
  ++counters_.patches;
  counters_.bytes += patch.data.count;
  return true;
}

std::size_t original_patch_bytes(const Mapper& map, const msg::MapPatch& patch, double z_low_m,
                                 double z_high_m) {
  const auto& g = map.geometry();
  const CellIndex lo = g.layer().cell_of(Vec2(patch.origin_x_m + 1e-6, patch.origin_y_m + 1e-6));
  const int z0 =
      std::max(0, static_cast<int>(std::floor((z_low_m - g.origin_z()) / g.resolution())));
  const int z1 = std::min(g.cells_z(),
                          static_cast<int>(std::ceil((z_high_m - g.origin_z()) / g.resolution())));
  std::size_t listed = 0;
  for (int z = z0; z < z1; ++z) {
    for (int y = lo.y; y < lo.y + patch.height_cells; ++y) {
      for (int x = lo.x; x < lo.x + patch.width_cells; ++x) {
        listed += map.state(VoxelIndex{x, y, z}) != VoxelState::kFree;
      }
    }
  }
  // map_info header: ids, resolution, origin, size, update box min/max (ROS Header + ~16 fields)
  // and two int32[] lengths.
  constexpr std::size_t kHeader = 16 + 2 * 4 + 8 + 3 * 8 + 3 * 4 + 6 * 8 + 2 * 4;
  return kHeader + 4 * listed;
}

}  // namespace colag::uav
