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
// How far a half's part of a ray stops short of the sensor's row (and the rest starts inside it).
constexpr double kEdge_m = 1e-7;
// The y of the boundary between the sensor's voxel row and the half on `side` (-1 south, +1 north).
double row_edge_y(const GridGeometry3d& g, int sensor_row, int side) {
  return g.origin_y() + (sensor_row + (side < 0 ? 0 : 1)) * g.resolution();
}
// The point of the segment from -> to at height y (clamped to the segment).
Vec3 point_at_y(const Vec3& from, const Vec3& to, double y) {
  const Vec3 d = to - from;
  return from + std::clamp((y - from.y()) / d.y(), 0.0, 1.0) * d;
}
// The per-scan bit sets, one bit per voxel.
bool test_bit(const std::uint64_t* words, std::size_t i) {
  return (words[i >> 6] >> (i & 63)) & 1U;
}
void set_bit(std::uint64_t* words, std::size_t i) {
  words[i >> 6] |= std::uint64_t{1} << (i & 63);
}
}  // namespace

Mapper::Mapper(const MapperConfig& config, ForkJoin* fork_join)
    : config_(config),
      fork_join_(fork_join),
      hit_(to_units(config.p_hit)),
      miss_(to_units(config.p_miss)),
      min_(to_units(config.p_min)),
      max_(to_units(config.p_max)),
      occupied_(to_units(config.p_occupied)) {
  // The two halves touch disjoint voxels, but bits of touched_ share 64-bit words where rows
  // meet in memory. Within a layer that is only ever one half's row and the sensor's row; the
  // last row of a layer meets the first row of the next, which the halves could both reach
  // only if a ray could span (almost) the whole grid in y.
  const auto& g = geometry();
  const int reach_rows = static_cast<int>(std::ceil(config.max_range_m / g.resolution())) + 2;
  halves_disjoint_ = 2 * reach_rows < g.cells_y() - 1;
  logodds_.fill(kUnknown);
  touched_.fill(0);
}

VoxelState Mapper::state(VoxelIndex v) const {
  if (!geometry().contains(v)) return VoxelState::kUnknown;
  return state_of(logodds_[geometry().index(v)]);
}

// Pointers and bounds are passed in (not read from members) so that the hot loops keep them in
// registers: the map's int8 writes may alias any memory.
inline bool Mapper::add_once(std::int8_t* logodds, std::uint64_t* touched, std::size_t i, int delta,
                             int lo, int hi) {
  set_bit(touched, i);
  const int old = logodds[i];
  const int now = std::clamp((old == kUnknown ? 0 : old) + delta, lo, hi);
  logodds[i] = static_cast<std::int8_t>(now);
  return now != old;
}

// Rays are traced backwards, from the end towards the sensor: the end voxel gets a hit (already
// applied) or a miss, every voxel on the way a miss. Near the sensor the rays of a scan form a
// dense fan, so a ray stops early once it has crossed `early_stop_voxels` consecutive voxels it
// did not change (updated earlier in this scan, or already saturated free), or
// `early_stop_crossed` consecutive voxels an earlier ray of this scan crossed: from there on the
// earlier rays have done the work. Stopping early only ever skips miss updates, so it never
// creates free space (a test compares it with full tracing).
bool Mapper::trace(const Vec3& a, const Vec3& b, bool first_is_end, bool hit, Runs& runs,
                   Part& part) {
  // Everything the loop touches is a local: the map's int8 writes may alias any memory, so
  // members, counters and the runs would otherwise be reloaded and stored at every voxel.
  std::int8_t* const logodds = logodds_.data();
  std::uint64_t* const touched = touched_.data();
  const int lo = min_, hi = max_, miss = miss_;
  const int stop_unchanged = config_.early_stop_voxels;
  const int stop_crossed = config_.early_stop_crossed;
  int unchanged = runs.unchanged, crossed = runs.crossed;
  std::uint64_t visits = 0, updates = 0;
  const auto apply = [&](std::size_t i, int delta) {
    ++updates;
    return add_once(logodds, touched, i, delta, lo, hi);
  };
  const bool stopped = any_voxel_index_on_segment(geometry(), a, b, [&](std::size_t i) {
    ++visits;
    const bool seen = test_bit(touched, i);
    if (first_is_end) {
      first_is_end = false;
      if (!seen) apply(i, hit ? hit_ : miss);  // a hit was applied already
      return false;
    }
    if (seen) {
      ++crossed;
      return ++unchanged >= stop_unchanged || crossed >= stop_crossed;
    }
    crossed = 0;
    if (apply(i, miss)) {
      unchanged = 0;
      return false;
    }
    return ++unchanged >= stop_unchanged;
  });
  runs = {unchanged, crossed};
  part.voxel_visits += visits;
  part.voxel_updates += updates;
  return !stopped;
}

template <class F>
void Mapper::both(F&& part) {
  if (fork_join_ != nullptr && halves_disjoint_) {
    fork_join_->run(2, part);
  } else {
    part(0);
    part(1);
  }
}

// Rays [from, to) of the scan (points, then misses) in world coordinates: cut at the maximum
// range and where they leave the mapped box (the grid's `top_layers` lowest layers), with their
// end voxel. Each ray is computed on its own, so any split of the range gives the same rays.
void Mapper::prepare(const Pose3& sensor, const hal::LidarScanView& scan, int top_layers,
                     std::size_t from, std::size_t to, Part& part) {
  const auto& g = geometry();
  const Mat3 R = sensor.q.toRotationMatrix();
  const double inv_res = 1.0 / g.resolution();  // as GridGeometry3d::voxel_of computes
  const Vec3 lo(g.origin_x(), g.origin_y(), g.origin_z());
  // The mapped box in voxels.
  const Vec3 size(g.cells_x(), g.cells_y(), top_layers);
  const Vec3 hi = lo + g.resolution() * size;
  for (std::size_t k = from; k < to; ++k) {
    const bool returns = k < scan.points.size();
    const hal::LidarPoint& p = returns ? scan.points[k] : scan.misses[k - scan.points.size()];
    Ray& ray = rays_[k];
    const Vec3 local(p.x_m, p.y_m, p.z_m);
    if (!all_finite(local)) {
      ray.row = -1;
      ++part.rays_outside;
      continue;
    }
    const double max_r = config_.max_range_m;
    const double r2 = local.squaredNorm();
    const bool within = r2 <= max_r * max_r;
    Vec3 end = sensor.p + R * (within ? local : local * (max_r / std::sqrt(r2)));
    // The end in voxel units: inside the box, the voxel index is its truncation (no floor, no
    // index round trip: this loop runs for every ray of every scan).
    Vec3 u = (end - lo) * inv_res;
    ray.hit = returns && within;
    if (!((u.array() >= 0.0).all() && (u.array() < size.array()).all())) {
      const Vec3 d = end - sensor.p;
      double t = 1.0;
      for (int a = 0; a < 3; ++a) {
        if (d[a] > 0) t = std::min(t, (hi[a] - sensor.p[a]) / d[a]);
        if (d[a] < 0) t = std::min(t, (lo[a] - sensor.p[a]) / d[a]);
      }
      end = sensor.p + std::max(0.0, t - 1e-6) * d;
      ray.hit = false;
      u = ((end - lo) * inv_res).cwiseMax(0.0).cwiseMin(size - Vec3::Constant(0.5));
    }
    ray.end = end;
    const VoxelIndex v{static_cast<int>(u.x()), static_cast<int>(u.y()), static_cast<int>(u.z())};
    ray.voxel = static_cast<std::uint32_t>(g.index(v));
    ray.row = static_cast<std::int16_t>(v.y);
  }
}

// Rays ending in a voxel that an earlier ray of this scan already ended in are dropped (OctoMap's
// "discretize"): from the same origin to the same voxel they are at most a voxel's width apart
// and cross the same voxels up to boundary grazing (about 2/3 of a VLP-32 scan at 0.1 m). Returns
// come first in the scan, so a voxel with a return keeps it, and all hits are applied before any
// ray is traced, so that the crossings of other rays do not wipe them out.
void Mapper::merge_and_hit(int row_lo, int row_hi, Part& part) {
  for (Ray& ray : rays_) {
    if (ray.row < row_lo || ray.row > row_hi) continue;
    ray.merged = test_bit(ended_.data(), ray.voxel);  // only the half owning the row writes it
    if (ray.merged) {
      ++part.rays_merged;
      continue;
    }
    set_bit(ended_.data(), ray.voxel);
    if (ray.hit && !test_bit(touched_.data(), ray.voxel)) {
      add_once(logodds_.data(), touched_.data(), ray.voxel, hit_, min_, max_);
      ++part.voxel_updates;
    }
  }
}

// One half of a scan: the rays that end south (side -1) or north (+1) of the sensor's voxel row,
// traced up to just before that row; those that get there are resumed later, in insert_scan.
// Rays ending in one half only ever cross voxels of that half or of the sensor's row, so the
// two halves can run at the same time.
void Mapper::trace_half(const Vec3& origin, int sensor_row, int side, Part& part) {
  const auto& g = geometry();
  const int row_lo = side < 0 ? 0 : sensor_row + 1;
  const int row_hi = side < 0 ? sensor_row - 1 : g.cells_y() - 1;
  merge_and_hit(row_lo, row_hi, part);
  const double edge_y = row_edge_y(g, sensor_row, side) + side * kEdge_m;  // just outside the row
  for (std::uint32_t k = 0; k < rays_.size(); ++k) {
    const Ray& ray = rays_[k];
    if (ray.row < row_lo || ray.row > row_hi || ray.merged) continue;
    Runs runs;
    if (trace(ray.end, point_at_y(ray.end, origin, edge_y), true, ray.hit, runs, part)) {
      (void)part.resume.push_back({k, static_cast<std::uint8_t>(std::min(runs.unchanged, 255)),
                                   static_cast<std::uint8_t>(std::min(runs.crossed, 255))});
    }
  }
}

void Mapper::insert_scan(const Pose3& sensor, const hal::LidarScanView& scan) {
  ++counters_.scans;
  const auto& g = geometry();
  const std::size_t total = scan.points.size() + scan.misses.size();
  const VoxelIndex sensor_voxel = g.voxel_of(sensor.p);
  if (!g.contains(sensor_voxel) || !all_finite(sensor.p)) {
    counters_.rays_outside += total;
    return;
  }
  const std::size_t n = std::min(total, rays_.capacity());
  counters_.rays_outside += total - n;
  (void)rays_.resize(n);
  for (Part& part : parts_) {
    part.resume.clear();
    part.rays_outside = part.rays_merged = part.voxel_updates = part.voxel_visits = 0;
  }

  // The layers mapped: up to the ceiling (rounded up to a voxel boundary), at least up to the
  // sensor's layer, at most the grid.
  const double ceiling_layers = (config_.ceiling_m - g.origin_z()) / g.resolution();
  const double bounded = std::isnan(ceiling_layers) ? 1e6 : std::clamp(ceiling_layers, 0.0, 1e6);
  const int top_layers =
      std::clamp(static_cast<int>(std::ceil(bounded - 1e-9)), sensor_voxel.z + 1, g.cells_z());

  // 1. Clear the per-scan bits and compute the rays, each part a half of both.
  both([&](int k) {
    const std::size_t words = touched_.size(), w0 = k == 0 ? 0 : words / 2,
                      w1 = k == 0 ? words / 2 : words;
    std::fill(touched_.begin() + w0, touched_.begin() + w1, 0);
    std::fill(ended_.begin() + w0, ended_.begin() + w1, 0);
    prepare(sensor, scan, top_layers, k == 0 ? 0 : n / 2, k == 0 ? n / 2 : n, parts_[k]);
  });
  // 2. The halves south and north of the sensor's row.
  const int sensor_row = sensor_voxel.y;
  both([&](int k) { trace_half(sensor.p, sensor_row, k == 0 ? -1 : 1, parts_[k]); });
  // 3. The sensor's row: the rays that end in it, then the rest of those that reached it.
  Part& serial = parts_[0];
  merge_and_hit(sensor_row, sensor_row, serial);
  for (const Ray& ray : rays_) {
    Runs runs;
    if (ray.row == sensor_row && !ray.merged)
      (void)trace(ray.end, sensor.p, true, ray.hit, runs, serial);
  }
  for (int k = 0; k < 2; ++k) {
    const int side = k == 0 ? -1 : 1;
    const double edge_y = row_edge_y(g, sensor_row, side) - side * kEdge_m;  // just inside the row
    for (const Part::Resume& r : parts_[static_cast<std::size_t>(k)].resume) {
      const Ray& ray = rays_[r.ray];
      Runs runs{r.unchanged, r.crossed};
      (void)trace(point_at_y(ray.end, sensor.p, edge_y), sensor.p, false, false, runs, serial);
      ++counters_.rays_resumed;
    }
  }
  counters_.rays += n - parts_[0].rays_outside - parts_[1].rays_outside;
  for (const Part& part : parts_) {
    counters_.rays_outside += part.rays_outside;
    counters_.rays_merged += part.rays_merged;
    counters_.voxel_updates += part.voxel_updates;
    counters_.voxel_visits += part.voxel_visits;
  }
}

}  // namespace colag::uav
