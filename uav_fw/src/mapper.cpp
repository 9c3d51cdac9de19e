#include "colag/uav/mapper.hpp"

#include <algorithm>
#include <cmath>

namespace colag::uav {

namespace {
constexpr double kScale = 50.0;  // log-odds units per int8 step
std::int8_t to_units(double p) {
  const double l = std::log(p / (1.0 - p)) * kScale;
  return static_cast<std::int8_t>(std::clamp(std::lround(l), -127L, 127L));
}
}  // namespace

Mapper::Mapper(const MapperConfig& config)
    : config_(config),
      hit_(to_units(config.p_hit)),
      miss_(to_units(config.p_miss)),
      min_(to_units(config.p_min)),
      max_(to_units(config.p_max)),
      occupied_(to_units(config.p_occupied)) {
  logodds_.fill(kUnknown);
  touched_.fill(0);
}

VoxelState Mapper::state(VoxelIndex v) const {
  if (!geometry().contains(v)) return VoxelState::kUnknown;
  return state_of(logodds_[geometry().index(v)]);
}

inline bool Mapper::update(std::size_t i, std::int8_t delta) {
  std::uint64_t& word = touched_[i >> 6];
  const std::uint64_t bit = std::uint64_t{1} << (i & 63);
  if (word & bit) return false;  // once per scan; hits were applied first
  word |= bit;
  const std::int8_t old = logodds_[i];
  const int base = old == kUnknown ? 0 : old;
  logodds_[i] = static_cast<std::int8_t>(
      std::clamp(base + delta, static_cast<int>(min_), static_cast<int>(max_)));
  ++counters_.voxel_updates;
  return logodds_[i] != old;
}

// The end voxel gets a hit when the ray ended on a return (a miss otherwise); every voxel the
// ray crossed on the way gets a miss. Traced backwards, from the end towards the sensor, and
// stopped once the ray has crossed `early_stop_voxels` consecutive voxels that this update
// did not change (already updated in this scan, or already saturated free) in
// this scan: near the sensor the rays of a scan form a dense fan, so everything nearer has
// been updated by the rays before (the first rays of a scan trace all the way).
void Mapper::trace(const Vec3& origin, const Vec3& end, bool hit) {
  const auto& g = geometry();
  // Clip the far end into the grid (rays may leave it, e.g. through the ceiling).
  Vec3 far = end;
  bool ends_inside = g.contains(g.voxel_of(end));
  if (!ends_inside) {
    const Vec3 lo(g.origin_x(), g.origin_y(), g.origin_z());
    const Vec3 hi = lo + g.resolution() * Vec3(g.cells_x(), g.cells_y(), g.cells_z());
    const Vec3 d = end - origin;
    double t1 = 1.0;
    for (int k = 0; k < 3; ++k) {
      if (d[k] > 0) t1 = std::min(t1, (hi[k] - origin[k]) / d[k]);
      if (d[k] < 0) t1 = std::min(t1, (lo[k] - origin[k]) / d[k]);
    }
    far = origin + std::max(0.0, t1 - 1e-6) * d;
    hit = false;
  }
  const std::size_t first = g.index(g.voxel_of(far));
  int run = 0;
  any_voxel_index_on_segment(g, far, origin, [&](std::size_t i) {
    if (i == first) {
      update(i, hit ? hit_ : miss_);
      return false;
    }
    if (!update(i, miss_)) return ++run >= config_.early_stop_voxels;
    run = 0;
    return false;
  });
}

void Mapper::insert_scan(const Pose3& sensor, const hal::LidarScanView& scan) {
  ++counters_.scans;
  touched_.fill(0);
  ended_.fill(0);
  const auto& g = geometry();
  if (!g.contains(g.voxel_of(sensor.p)) || !all_finite(sensor.p)) {
    counters_.rays_outside += scan.points.size() + scan.misses.size();
    return;
  }
  // 1. Every ray's world end point (cut at the maximum range), once.
  const Mat3 R = sensor.q.toRotationMatrix();
  rays_.clear();
  const auto collect = [&](std::span<const hal::LidarPoint> points, bool returns) {
    for (const hal::LidarPoint& p : points) {
      const Vec3 local(p.x_m, p.y_m, p.z_m);
      if (!all_finite(local) || rays_.full()) {
        ++counters_.rays_outside;
        continue;
      }
      const double r = local.norm();
      const bool within = r <= config_.max_range_m;
      const Vec3 end = sensor.p + R * (within ? local : local * (config_.max_range_m / r));
      (void)rays_.push_back({end, returns && within});
    }
  };
  collect(scan.points, true);
  collect(scan.misses, false);
  // 2. Returns first, so that their voxels keep the hit in this scan.
  for (const Ray& ray : rays_) {
    const VoxelIndex v = g.voxel_of(ray.end);
    if (ray.hit && g.contains(v)) update(g.index(v), hit_);
  }
  // 3. Trace. Rays ending in a voxel that an earlier ray of this scan already ended in are not
  //    traced again (OctoMap's "discretize"): from the same origin to the same voxel they are
  //    at most a voxel's width apart and cross the same voxels up to boundary grazing. About
  //    2/3 of a VLP-32 scan at 0.1 m. Counted in rays_merged.
  for (const Ray& ray : rays_) {
    ++counters_.rays;
    const VoxelIndex v = g.voxel_of(ray.end);
    if (g.contains(v)) {
      const std::size_t i = g.index(v);
      std::uint64_t& word = ended_[i >> 6];
      const std::uint64_t bit = std::uint64_t{1} << (i & 63);
      if (word & bit) {
        ++counters_.rays_merged;
        continue;
      }
      word |= bit;
    }
    trace(sensor.p, ray.end, ray.hit);
  }
}

}  // namespace colag::uav
