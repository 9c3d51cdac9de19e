#include "colag/uav/mapper.hpp"

#include <algorithm>
#include <cmath>

#include "colag/common/grid_shift.hpp"
#include "colag/common/map_window.hpp"

namespace colag::uav {

namespace {
constexpr double kScale = 50.0;  // log-odds units per int8 step
std::int8_t to_units(double p) {
  const double l = std::log(p / (1.0 - p)) * kScale;
  return static_cast<std::int8_t>(std::clamp(std::lround(l), -127L, 127L));
}
// How far inside the sensor's slice the rest of a ray that reached it starts.
constexpr double kEdge_m = 1e-7;
// Where the sensor's slice meets the half on `side` (-1 low, +1 high) along `axis`.
double slice_edge(const GridGeometry3d& g, int axis, int cell, int side) {
  const double origin = axis == 0 ? g.origin_x() : g.origin_y();
  return origin + (cell + (side < 0 ? 0 : 1)) * g.resolution();
}
// The point of the segment from -> to whose coordinate `axis` is `value` (clamped to the segment).
Vec3 point_at(const Vec3& from, const Vec3& to, int axis, double value) {
  const Vec3 d = to - from;
  return from + std::clamp((value - from[axis]) / d[axis], 0.0, 1.0) * d;
}
// The per-scan bit sets, one bit per voxel.
bool test_bit(const std::uint64_t* words, std::size_t i) {
  return (words[i >> 6] >> (i & 63)) & 1U;
}
void set_bit(std::uint64_t* words, std::size_t i) {
  words[i >> 6] |= std::uint64_t{1} << (i & 63);
}
void clear_bit(std::uint64_t* words, std::size_t i) {
  words[i >> 6] &= ~(std::uint64_t{1} << (i & 63));
}
}  // namespace

Mapper::Mapper(const MapperConfig& config, ForkJoin* fork_join)
    : config_(config),
      fork_join_(fork_join),
      hit_(to_units(config.p_hit)),
      miss_(to_units(config.p_miss)),
      weak_miss_(to_units(config.p_miss_inferred)),
      min_(to_units(config.p_min)),
      max_(to_units(config.p_max)),
      occupied_(to_units(config.p_occupied)) {
  const auto& g = geometry();
  const double reach = std::ceil(config.max_range_m / g.resolution()) + 2;
  reach_ = reach < std::max(g.cells_x(), g.cells_y()) ? static_cast<int>(reach)
                                                      : std::max(g.cells_x(), g.cells_y());
  logodds_.fill(kUnknown);
}

Status Mapper::move_to(const Vec2& origin) {
  const GridGeometry3d& g = geometry_;
  int dx = 0, dy = 0;
  if (Status s = window_step(g.layer(), origin, dx, dy); !s.is_ok()) return s;
  if (dx == 0 && dy == 0) return Status::ok();
  const std::size_t layer = g.layer().size();
  for (int z = 0; z < g.cells_z(); ++z) {
    shift_layer(logodds_.data() + static_cast<std::size_t>(z) * layer, g.cells_x(), g.cells_y(), dx,
                dy, kUnknown);
  }
  geometry_ = GridGeometry3d(g.origin_x() + dx * g.resolution(), g.origin_y() + dy * g.resolution(),
                             g.origin_z(), g.resolution(), g.cells_x(), g.cells_y(), g.cells_z());
  return Status::ok();
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
//
// An inferred miss (weak) ends at the voxel nearest the sensor that is occupied now: a beam that
// crossed an obstacle seen there most likely lost its return on it, and says nothing of what lies
// behind (the inside of a wall, its shadow). Traced backwards, the ray meets what lies behind
// first: its updates are logged and undone when an occupied voxel turns up. (The log lives for
// one call: a ray resumed in the sensor's slice cannot undo its half's updates. That takes an
// occupied voxel in the sensor's own 0.1 m row or column, crossed by a ray running almost along
// it, a few columns of a scan at most; those keep the weak miss's other rule: the occupied voxel
// itself is never lowered.)
bool Mapper::trace(const Vec3& a, const Vec3& b, VoxelLayer stop, bool first_is_end, bool hit,
                   bool weak, Runs& runs, Part& part, Bits& bits) {
  // Everything the loop touches is a local: the map's int8 writes may alias any memory, so
  // members, counters and the runs would otherwise be reloaded and stored at every voxel.
  std::int8_t* const logodds = logodds_.data();
  std::uint64_t* const touched = bits.touched.data();
  const int lo = min_, hi = max_, miss = weak ? weak_miss_ : miss_;
  // An inferred miss may be a return lost on this very surface: it never lowers a voxel that is
  // occupied now (a lost return cannot open a hole in a mapped obstacle). The rest of its way,
  // in front of and behind that voxel, is treated as before.
  const int keep_from = weak ? occupied_ : 128;  // 128: above every int8, nothing is kept
  const int stop_unchanged = config_.early_stop_voxels;
  const int stop_crossed = config_.early_stop_crossed;
  int unchanged = runs.unchanged, crossed = runs.crossed;
  std::uint64_t visits = 0, updates = 0;
  Part::Undo* const undo = part.undo.data();
  std::size_t logged = 0;
  const auto apply = [&](std::size_t i, int delta) {
    if (weak) {
      if (logged == part.undo.size()) return false;  // see Part::undo
      undo[logged++] = {static_cast<std::uint32_t>(i), logodds[i]};
    }
    ++updates;
    return add_once(logodds, touched, i, delta, lo, hi);
  };
  const auto undo_beyond = [&] {
    for (std::size_t k = 0; k < logged; ++k) {
      logodds[undo[k].voxel] = undo[k].logodds;
      clear_bit(touched, undo[k].voxel);
    }
    part.misses_undone += logged;
    logged = 0;
  };
  const bool stopped = any_voxel_index_on_segment(geometry(), a, b, stop, [&](std::size_t i) {
    ++visits;
    const bool seen = test_bit(touched, i);
    if (first_is_end) {
      first_is_end = false;
      if (!seen && (hit || logodds[i] < keep_from)) apply(i, hit ? hit_ : miss);  // hits: applied
      return false;
    }
    const bool kept = logodds[i] >= keep_from;  // only ever for an inferred miss
    if (kept) undo_beyond();
    if (seen) {
      ++crossed;
      return ++unchanged >= stop_unchanged || crossed >= stop_crossed;
    }
    crossed = 0;
    if (kept) return ++unchanged >= stop_unchanged;
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
void Mapper::in_parts(int parts, F&& part) {
  if (fork_join_ != nullptr) {
    fork_join_->run(parts, part);
  } else {
    for (int i = 0; i < parts; ++i)
      part(i);
  }
}

// The chunk's rays of the scan (points, then misses) in world coordinates: cut at the maximum
// range and where they leave the mapped box (the grid's `top_layers` lowest layers), with their
// end voxel, listed by where they end relative to the cut. Each ray is computed on its own, so
// any split into chunks gives the same rays.
void Mapper::prepare(const Pose3& sensor, const hal::LidarScanView& scan, int top_layers, Cut cut,
                     Chunk& chunk) {
  const auto& g = geometry();
  const Mat3 R = sensor.q.toRotationMatrix();
  const double inv_res = 1.0 / g.resolution();  // as GridGeometry3d::voxel_of computes
  const Vec3 lo(g.origin_x(), g.origin_y(), g.origin_z());
  const Vec3 size(g.cells_x(), g.cells_y(), top_layers);  // the mapped box in voxels
  const Vec3 sensor_u = (sensor.p - lo) * inv_res;
  const double max_r = config_.max_range_m;
  const std::size_t n_points = scan.points.size();
  const std::size_t stride_y = static_cast<std::size_t>(g.cells_x());
  const std::size_t stride_z = stride_y * static_cast<std::size_t>(g.cells_y());
  const std::size_t from = chunk.first, to = chunk.last;
  std::array<RayId*, 3> lists{ends_[kLow].data() + from, ends_[kHigh].data() + from,
                              ends_[kSlice].data() + from};
  std::array<std::uint32_t, 3> count{};
  std::uint64_t outside = 0;
  // The loop runs for every ray of every scan: scalar arithmetic in the order Eigen's would do
  // it (the same rounding), none read back from memory (a 16-byte load of two 8-byte stores just
  // made cannot be forwarded: Eigen's packets of the ray's end stalled this loop for a third of
  // its time), no index round trip (inside the box, the voxel is the truncation).
  for (std::size_t k = from; k < to; ++k) {
    const bool returns = k < n_points;
    const hal::LidarPoint& p = returns ? scan.points.data()[k] : scan.misses.data()[k - n_points];
    double lx = p.x_m, ly = p.y_m, lz = p.z_m;
    const double r2 = lx * lx + ly * ly + lz * lz;
    const bool within = r2 <= max_r * max_r;
    if (!within) {
      const double scale = max_r / std::sqrt(r2);
      lx *= scale;
      ly *= scale;
      lz *= scale;
    }
    const double ex = sensor.p.x() + (R(0, 0) * lx + R(0, 1) * ly + R(0, 2) * lz);
    const double ey = sensor.p.y() + (R(1, 0) * lx + R(1, 1) * ly + R(1, 2) * lz);
    const double ez = sensor.p.z() + (R(2, 0) * lx + R(2, 1) * ly + R(2, 2) * lz);
    Ray& ray = rays_[k];
    ray.end = Vec3(ex, ey, ez);
    ray.hit = returns && within;
    ray.weak = !returns && scan.misses_inferred;
    double ux = (ex - lo.x()) * inv_res, uy = (ey - lo.y()) * inv_res, uz = (ez - lo.z()) * inv_res;
    // A non-finite point ends up here too (NaN, or infinity scaled to NaN), and is dropped.
    // Six comparisons and-ed without a branch each (int: & on bools is a mistake to clang).
    const int inside = static_cast<int>(ux >= 0.0) & static_cast<int>(uy >= 0.0) &
                       static_cast<int>(uz >= 0.0) & static_cast<int>(ux < size.x()) &
                       static_cast<int>(uy < size.y()) & static_cast<int>(uz < size.z());
    if (inside == 0) {
      if (!std::isfinite(ux + uy + uz)) {
        ++outside;
        continue;
      }
      // Cut where the ray leaves the box: only the axes it leaves through need a division.
      double t = 1.0;
      const auto exit = [&](double u, double start, double top) {
        if (u >= top) t = std::min(t, (top - start) / (u - start));
        if (u < 0.0) t = std::min(t, -start / (u - start));
      };
      exit(ux, sensor_u.x(), size.x());
      exit(uy, sensor_u.y(), size.y());
      exit(uz, sensor_u.z(), size.z());
      t = std::max(0.0, t - 1e-6);
      const Vec3& s = sensor.p;
      const double cx = s.x() + t * (ex - s.x()), cy = s.y() + t * (ey - s.y()),
                   cz = s.z() + t * (ez - s.z());
      ray.end = Vec3(cx, cy, cz);
      ray.hit = false;
      const auto clamp = [](double u, double top) { return std::min(std::max(u, 0.0), top - 0.5); };
      ux = clamp((cx - lo.x()) * inv_res, size.x());
      uy = clamp((cy - lo.y()) * inv_res, size.y());
      uz = clamp((cz - lo.z()) * inv_res, size.z());
    }
    const VoxelIndex v{static_cast<int>(ux), static_cast<int>(uy), static_cast<int>(uz)};
    ray.voxel = static_cast<std::uint32_t>(static_cast<std::size_t>(v.z) * stride_z +
                                           static_cast<std::size_t>(v.y) * stride_y +
                                           static_cast<std::size_t>(v.x));
    const int along = cut.axis == 0 ? v.x : v.y;
    const End end = along < cut.cell ? kLow : (along > cut.cell ? kHigh : kSlice);
    lists[end][count[end]++] = static_cast<RayId>(k);
  }
  chunk.count = count;
  chunk.rays_outside = outside;
}

void Mapper::clear_bits(Bits& bits, int top_layers, int row_lo, int row_hi) const {
  const auto& g = geometry();
  row_lo = std::max(row_lo, 0);
  row_hi = std::min(row_hi, g.cells_y() - 1);
  if (row_lo > row_hi) return;
  for (int z = 0; z < top_layers; ++z) {
    const std::size_t w0 = g.index({0, row_lo, z}) >> 6;
    const std::size_t w1 = (g.index({g.cells_x() - 1, row_hi, z}) >> 6) + 1;
    std::fill(bits.touched.begin() + static_cast<std::ptrdiff_t>(w0),
              bits.touched.begin() + static_cast<std::ptrdiff_t>(w1), 0);
    std::fill(bits.ended.begin() + static_cast<std::ptrdiff_t>(w0),
              bits.ended.begin() + static_cast<std::ptrdiff_t>(w1), 0);
  }
}

// Rays ending in a voxel that an earlier ray of this scan already ended in are dropped (OctoMap's
// "discretize"): from the same origin to the same voxel they are at most a voxel's width apart
// and cross the same voxels up to boundary grazing (about 2/3 of a VLP-32 scan at 0.1 m). Returns
// come first in the scan, so a voxel with a return keeps it, and all hits are applied before any
// ray is traced, so that the crossings of other rays do not wipe them out. Only the caller
// tracing `end` touches these lists and these voxels.
void Mapper::merge_and_hit(End end, Part& part, Bits& bits) {
  std::uint64_t* const ended = bits.ended.data();
  std::uint64_t* const touched = bits.touched.data();
  const Ray* const rays = rays_.data();
  for (Chunk& chunk : chunks_) {  // in scan order
    const std::span<RayId> list = ends_of(end, chunk);
    RayId* const ids = list.data();
    const std::size_t n = list.size();
    // Kept or merged is a coin toss from ray to ray: written without a branch (always store,
    // count only the kept), since a mispredicted branch per ray cost more than the loop's work.
    std::size_t kept = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const RayId k = ids[j];
      const std::uint32_t v = rays[k].voxel;
      const bool first = !test_bit(ended, v);
      set_bit(ended, v);
      ids[kept] = k;
      kept += first ? 1U : 0U;
    }
    part.rays_merged += n - kept;
    chunk.count[end] = static_cast<std::uint32_t>(kept);
    for (std::size_t j = 0; j < kept; ++j) {
      const Ray& ray = rays[ids[j]];
      if (ray.hit && !test_bit(touched, ray.voxel)) {
        add_once(logodds_.data(), touched, ray.voxel, hit_, min_, max_);
        ++part.voxel_updates;
      }
    }
  }
}

// One half of a scan: the rays that end on the low (side -1) or high (+1) side of the sensor's
// slice, traced up to the slice (the traversal runs out of room in front of it: no division for
// where the ray meets it); those that get there are resumed later, in insert_scan. Rays ending
// in one half only ever cross voxels of that half or of the slice, so the two halves can run at
// the same time.
void Mapper::trace_half(const Vec3& origin, Cut cut, int side, Part& part, Bits& bits) {
  const End end = side < 0 ? kLow : kHigh;
  merge_and_hit(end, part, bits);
  const VoxelLayer slice{cut.axis, cut.cell};
  for (const Chunk& chunk : chunks_) {
    for (const RayId k : ends_of(end, chunk)) {
      const Ray& ray = rays_[k];
      Runs runs;
      if (trace(ray.end, origin, slice, true, ray.hit, ray.weak, runs, part, bits)) {
        (void)part.resume.push_back({k, static_cast<std::uint8_t>(std::min(runs.unchanged, 255)),
                                     static_cast<std::uint8_t>(std::min(runs.crossed, 255))});
      }
    }
  }
}

template <class Map, class Visit>
void Mapper::for_each_hit(Map& self, const Vec2& centre, double radius_m, double z_low_m,
                          double z_high_m, Visit&& visit) {
  const auto& g = self.geometry();
  if (!all_finite(centre) || !(radius_m >= 0.0) || !(z_low_m <= z_high_m)) return;
  const double r = std::min(radius_m, 1e3);
  const VoxelIndex lo = g.voxel_of(Vec3(centre.x() - r, centre.y() - r, z_low_m));
  const VoxelIndex hi = g.voxel_of(Vec3(centre.x() + r, centre.y() + r, z_high_m));
  for (int z = std::max(lo.z, 0); z <= std::min(hi.z, g.cells_z() - 1); ++z) {
    for (int y = std::max(lo.y, 0); y <= std::min(hi.y, g.cells_y() - 1); ++y) {
      for (int x = std::max(lo.x, 0); x <= std::min(hi.x, g.cells_x() - 1); ++x) {
        const Vec3 c = g.center_of({x, y, z});
        if ((c.head<2>() - centre).squaredNorm() > r * r || c.z() < z_low_m || c.z() > z_high_m)
          continue;
        auto& v = self.logodds_[g.index({x, y, z})];
        if (v == kUnknown || v <= 0) continue;  // seen free more than hit: not a body
        visit(v);
      }
    }
  }
}

std::size_t Mapper::forget(const Vec2& centre, double radius_m, double z_low_m, double z_high_m) {
  std::size_t known = 0;
  for_each_hit(*this, centre, radius_m, z_low_m, z_high_m, [&](std::int8_t& v) {
    ++known;
    v = kUnknown;
  });
  counters_.voxels_forgotten += known;
  return known;
}

std::size_t Mapper::count_hit(const Vec2& centre, double radius_m, double z_low_m,
                              double z_high_m) const {
  std::size_t n = 0;
  for_each_hit(*this, centre, radius_m, z_low_m, z_high_m, [&](const std::int8_t&) { ++n; });
  return n;
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
    part.rays_merged = part.voxel_updates = part.voxel_visits = part.misses_undone = 0;
  }
  for (int c = 0; c < kChunks; ++c) {
    chunks_[static_cast<std::size_t>(c)].first = static_cast<std::uint32_t>(n * c / kChunks);
    chunks_[static_cast<std::size_t>(c)].last = static_cast<std::uint32_t>(n * (c + 1) / kChunks);
  }

  // The layers mapped: up to the ceiling (rounded up to a voxel boundary), at least up to the
  // sensor's layer, at most the grid.
  const double ceiling_layers = (config_.ceiling_m - g.origin_z()) / g.resolution();
  const double bounded = std::isnan(ceiling_layers) ? 1e6 : std::clamp(ceiling_layers, 0.0, 1e6);
  const int top_layers =
      std::clamp(static_cast<int>(std::ceil(bounded - 1e-9)), sensor_voxel.z + 1, g.cells_z());

  // The cut: by column when the sensor moved more along y than along x since the last scan
  // (the new ground ahead then falls into both halves), by row when it moved more along x.
  Cut cut;
  const Vec3 moved = sensor.p - last_sensor_;
  switch (config_.split) {
    case MapperSplit::kRows:
      cut.axis = 1;
      break;
    case MapperSplit::kColumns:
      cut.axis = 0;
      break;
    case MapperSplit::kAlongMotion:
      cut.axis = std::abs(moved.y()) > std::abs(moved.x())
                     ? 0
                     : (std::abs(moved.x()) > std::abs(moved.y()) ? 1 : last_axis_);
      break;
  }
  last_sensor_ = sensor.p;
  last_axis_ = cut.axis;
  cut.cell = cut.axis == 0 ? sensor_voxel.x : sensor_voxel.y;
  counters_.scans_by_column += cut.axis == 0 ? 1U : 0U;

  // 1. Clear the per-scan bits (each half its own, where its rays can reach; half 0's also
  // cover the sensor's slice: the first two chunks do it) and compute the rays, by chunk.
  in_parts(kChunks, [&](int c) {
    const int row = sensor_voxel.y;
    if (c < 2) {
      if (cut.axis == 1) {
        clear_bits(bits_[c], top_layers, c == 0 ? row - reach_ : row + 1,
                   c == 0 ? row : row + reach_);
      } else {
        clear_bits(bits_[c], top_layers, row - reach_, row + reach_);
      }
    }
    prepare(sensor, scan, top_layers, cut, chunks_[static_cast<std::size_t>(c)]);
  });
  // 2. The halves on both sides of the sensor's slice.
  in_parts(2, [&](int k) { trace_half(sensor.p, cut, k == 0 ? -1 : 1, parts_[k], bits_[k]); });
  // 3. The slice: the rays that end in it, then the rest of those that reached it.
  Part& serial = parts_[0];
  Bits& bits = bits_[0];
  merge_and_hit(kSlice, serial, bits);
  for (const Chunk& chunk : chunks_) {
    for (const RayId k : ends_of(kSlice, chunk)) {
      Runs runs;
      (void)trace(rays_[k].end, sensor.p, VoxelLayer{}, true, rays_[k].hit, rays_[k].weak, runs,
                  serial, bits);
    }
  }
  for (int k = 0; k < 2; ++k) {
    const int side = k == 0 ? -1 : 1;
    const double edge = slice_edge(g, cut.axis, cut.cell, side) - side * kEdge_m;  // inside
    for (const Part::Resume& r : parts_[static_cast<std::size_t>(k)].resume) {
      const Ray& ray = rays_[r.ray];
      Runs runs{r.unchanged, r.crossed};
      (void)trace(point_at(ray.end, sensor.p, cut.axis, edge), sensor.p, VoxelLayer{}, false, false,
                  ray.weak, runs, serial, bits);
      ++counters_.rays_resumed;
    }
  }
  counters_.rays += n;
  for (const Chunk& chunk : chunks_) {
    counters_.rays -= chunk.rays_outside;
    counters_.rays_outside += chunk.rays_outside;
  }
  for (const Part& part : parts_) {
    counters_.rays_merged += part.rays_merged;
    counters_.voxel_updates += part.voxel_updates;
    counters_.voxel_visits += part.voxel_visits;
    counters_.misses_undone += part.misses_undone;
  }
}

}  // namespace colag::uav
