#pragma once
// The UAV's 3-D occupancy map (paper Sec. III-B): a log-odds voxel grid at 0.1 m over the
// limits-header extent, in static storage. Each LiDAR ray is traced with an exact voxel
// traversal (Amanatides-Woo): the voxels it crosses become more likely free, the voxel of its
// return more likely occupied. Within one scan a voxel is updated at most once, and a return
// wins over a crossing (as OctoMap does), so thousands of rays crossing the space around the
// sensor do not wipe out an obstacle seen in the same scan. Never-observed voxels stay unknown:
// occlusion shadows behind obstacles and the blind cone under the sensor.
//
// Log-odds are stored as int8 in units of 1/50 (exact, deterministic integer updates):
// defaults p_hit 0.85, p_miss 0.35, clamped to [0.12, 0.90], occupied at >= 0.80.
#include <array>
#include <cstdint>

#include "colag/common/grid3d.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/hal/lidar.hpp"

namespace colag::uav {

struct MapperConfig {
  double p_hit = 0.85;
  double p_miss = 0.35;
  double p_min = 0.12;
  double p_max = 0.90;
  double p_occupied = 0.80;
  double max_range_m = 15.0;   // longer returns are treated as misses at this range
  int early_stop_voxels = 10;  // see Mapper::trace; a huge value traces every ray fully
};

enum class VoxelState : std::uint8_t { kUnknown, kFree, kOccupied };

struct MapperCounters {
  std::uint64_t scans = 0;
  std::uint64_t rays = 0;
  std::uint64_t voxel_updates = 0;
  std::uint64_t rays_outside = 0;  // sensor outside the grid, or non-finite points
  std::uint64_t rays_merged = 0;   // ended in a voxel an earlier ray of the scan ended in
};

class Mapper {
 public:
  explicit Mapper(const MapperConfig& config = {});

  // Integrates one scan taken from `sensor` (sensor frame -> world).
  void insert_scan(const Pose3& sensor, const hal::LidarScanView& scan);

  const GridGeometry3d& geometry() const { return kWorldGrid3d; }
  VoxelState state(VoxelIndex v) const;
  // One x-row of raw log-odds (cells_x values) for fast, cache-friendly scans of a layer.
  const std::int8_t* row(int y, int z) const { return &logodds_[geometry().index({0, y, z})]; }
  VoxelState state_of(std::int8_t raw) const {
    return raw == kUnknown ? VoxelState::kUnknown
                           : (raw >= occupied_ ? VoxelState::kOccupied : VoxelState::kFree);
  }
  VoxelState state(const Vec3& p) const { return state(geometry().voxel_of(p)); }
  bool observed(VoxelIndex v) const { return state(v) != VoxelState::kUnknown; }
  const MapperCounters& counters() const { return counters_; }

 private:
  static constexpr std::int8_t kUnknown = -128;
  void trace(const Vec3& origin, const Vec3& end, bool hit);
  // Applies `delta` once per scan (later calls are ignored); true if the voxel changed.
  bool update(std::size_t i, std::int8_t delta);

  MapperConfig config_;
  std::int8_t hit_, miss_, min_, max_, occupied_;
  MapperCounters counters_;
  std::array<std::int8_t, limits::kGridCells3d> logodds_;
  // One bit per voxel: updated in the current scan. 600 KB, so it stays in cache while the
  // rays of a scan cross the same voxels again and again; cleared at every scan.
  std::array<std::uint64_t, (limits::kGridCells3d + 63) / 64> touched_;
  std::array<std::uint64_t, (limits::kGridCells3d + 63) / 64>
      ended_;  // a ray of this scan ended here
  struct Ray {
    Vec3 end = Vec3::Zero();  // world frame, cut at max range
    bool hit = false;         // ends on a return
  };
  StaticVector<Ray, limits::kMaxLidarPoints> rays_;  // the scan being inserted
};

}  // namespace colag::uav
