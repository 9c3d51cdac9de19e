#pragma once
// The UAV's 3-D occupancy map (paper Sec. III-B): a log-odds voxel grid at 0.1 m of the
// limits-header size, in static storage: a window of the site that moves with the UAV. Each LiDAR
// ray is traced with an exact voxel traversal (Amanatides-Woo): the voxels it crosses become more
// likely free, the voxel of its return more likely occupied. Within one scan a voxel is updated at
// most once, and a return wins over a crossing (as OctoMap does), so thousands of rays crossing the
// space around the sensor do not wipe out an obstacle seen in the same scan. Never-observed voxels
// stay unknown: occlusion shadows behind obstacles and the blind cone under the sensor.
//
// Log-odds are stored as int8 in units of 1/50 (exact, deterministic integer updates):
// defaults p_hit 0.85, p_miss 0.35, clamped to [0.12, 0.90], occupied at >= 0.80.
//
// Two cores: rays ending south of the sensor's voxel row only cross voxels south of it or in
// it (the same for north), so a scan is traced as two halves that touch disjoint voxels, each
// up to the sensor's row, then the row itself. The same works with the sensor's column (west
// and east halves); by default the cut runs along the UAV's motion, so that both halves get
// half of the new ground ahead. Given a ForkJoin the halves run at the same time; the map is
// the same either way (tested), since the split never depends on it.
#include <array>
#include <cstdint>
#include <limits>
#include <span>

#include "colag/common/fork_join.hpp"
#include "colag/common/grid3d.hpp"
#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/status.hpp"
#include "colag/hal/lidar.hpp"

namespace colag::uav {

// How a scan is cut into two halves (see the top of the file).
enum class MapperSplit : std::uint8_t {
  kAlongMotion,  // by column when the sensor moved more along y than x since the last scan
  kRows,         // south / north of the sensor's voxel row
  kColumns,      // west / east of the sensor's voxel column
};

struct MapperConfig {
  double p_hit = 0.85;
  double p_miss = 0.35;
  // A miss the firmware inferred (a beam of the pattern with no return: see no_return_beams.hpp)
  // may be a return lost on a dark surface: it ends at the first voxel on its way that is
  // occupied now (nothing behind it is lowered: the inside of a wall, its shadow), never lowers
  // that voxel, and counts less elsewhere (four of them undo one hit), so a lost return does not
  // open a hole in a box, seen or half-seen.
  double p_miss_inferred = 0.47;
  double p_min = 0.12;
  double p_max = 0.90;
  double p_occupied = 0.80;
  double max_range_m = 15.0;  // longer returns are treated as misses at this range
  // Rays are cut where they rise through this height (no hit there), as at the grid's edge:
  // nothing above the highest layer anyone reads is worth tracing (the supervisor sets it to
  // the top of its flight layer or of the UGVs' body band). Always at least a voxel above the
  // sensor, so that a UAV flying higher still maps what it flies through.
  double ceiling_m = std::numeric_limits<double>::infinity();
  // Early stop of a ray's back-trace (see Mapper::trace): after this many consecutive voxels it
  // did not change, or after this many consecutive voxels an earlier ray of the same scan
  // already crossed. Huge values trace every ray fully.
  int early_stop_voxels = 10;
  int early_stop_crossed = 3;
  MapperSplit split = MapperSplit::kAlongMotion;
};

enum class VoxelState : std::uint8_t { kUnknown, kFree, kOccupied };

struct MapperCounters {
  std::uint64_t scans = 0;
  std::uint64_t rays = 0;
  std::uint64_t voxel_updates = 0;
  std::uint64_t voxel_visits = 0;     // voxels the traces stepped through (incl. early-stop runs)
  std::uint64_t rays_outside = 0;     // sensor outside the grid, or non-finite points
  std::uint64_t rays_merged = 0;      // ended in a voxel an earlier ray of the scan ended in
  std::uint64_t rays_resumed = 0;     // back-traces finished in the sensor's row or column
  std::uint64_t scans_by_column = 0;  // scans cut into west and east halves
  std::uint64_t voxels_forgotten = 0;
  std::uint64_t misses_undone = 0;  // inferred-miss updates undone: beyond an occupied voxel
};

class Mapper {
 public:
  // `fork_join` (optional, not owned) lets the tracing of a scan use several cores; the map is
  // the same with or without it.
  explicit Mapper(const MapperConfig& config = {}, ForkJoin* fork_join = nullptr);

  // Integrates one scan taken from `sensor` (sensor frame -> world).
  void insert_scan(const Pose3& sensor, const hal::LidarScanView& scan);
  // Back to unknown: the voxels whose centres lie within `radius_m` of `centre` (horizontally)
  // and between z_low_m and z_high_m, and that were hit more than seen free. What was mapped
  // there is no longer believed (a robot turned out to stand there); what was seen free stays
  // free (it was not the robot). Returns how many voxels were forgotten.
  std::size_t forget(const Vec2& centre, double radius_m, double z_low_m, double z_high_m);
  // How many voxels forget() would forget there (hit more than seen free).
  std::size_t count_hit(const Vec2& centre, double radius_m, double z_low_m, double z_high_m) const;

  // The window of the site this map holds: limits' size, at kWorldGrid3d's place until moved.
  const GridGeometry3d& geometry() const { return geometry_; }
  // Moves the window (horizontally) so that its corner is at `origin`, on the grid's lattice:
  // the voxels it keeps keep their log-odds, the voxels that enter it are unknown (~2 ms for
  // the whole grid: for a UAV that nears its window's edge, not for every scan). Refused (map
  // unchanged) off the lattice or not finite.
  Status move_to(const Vec2& origin);
  VoxelState state(VoxelIndex v) const;
  // One x-row of raw log-odds (cells_x values) for fast, cache-friendly scans of a layer.
  const std::int8_t* row(int y, int z) const { return &logodds_[geometry().index({0, y, z})]; }
  VoxelState state_of(std::int8_t raw) const {
    return raw == kUnknown ? VoxelState::kUnknown
                           : (raw >= occupied_ ? VoxelState::kOccupied : VoxelState::kFree);
  }
  // The raw values behind state_of, for vectorised scans of rows: unknown, and the lowest
  // occupied (every raw value at or above it is occupied, every other known one free).
  static constexpr std::int8_t raw_unknown() { return kUnknown; }
  std::int8_t raw_occupied() const { return occupied_; }
  VoxelState state(const Vec3& p) const { return state(geometry().voxel_of(p)); }
  bool observed(VoxelIndex v) const { return state(v) != VoxelState::kUnknown; }
  const MapperCounters& counters() const { return counters_; }

 private:
  static constexpr std::int8_t kUnknown = -128;
  // Calls visit(log-odds) for each voxel that forget() and count_hit() consider.
  template <class Map, class Visit>
  static void for_each_hit(Map& self, const Vec2& centre, double radius_m, double z_low_m,
                           double z_high_m, Visit&& visit);
  // A ray's number in the scan (rays_): 16 bits hold every scan the limits allow.
  using RayId = std::uint16_t;
  static_assert(limits::kMaxLidarPoints <= 65536);
  struct Ray {
    Vec3 end = Vec3::Zero();  // world frame, cut at the maximum range and at the grid's edge
    std::uint32_t voxel = 0;  // linear index of the end voxel
    bool hit = false;         // ends on a return
    bool weak = false;        // an inferred miss (MapperConfig::p_miss_inferred)
  };
  // Where a ray ends, relative to the sensor's voxel slice (its row or column): it decides who
  // traces it. Low: the lower indices (south or west).
  enum End : std::uint8_t { kLow = 0, kHigh = 1, kSlice = 2 };
  // The cut of the current scan: axis 0 (x) = by the sensor's column, 1 (y) = by its row.
  struct Cut {
    int axis = 1;
    int cell = 0;  // the sensor's voxel index along the axis
  };
  // The per-scan bits of one half, one per voxel: updated in this scan, a ray of this scan
  // ended here. 600 KB each, so they stay in cache while the rays of a scan cross the same
  // voxels again and again. One set per half: the halves never write the same 64-bit word.
  struct Bits {
    std::array<std::uint64_t, (limits::kGridCells3d + 63) / 64> touched, ended;
  };
  // The rays are prepared in chunks of consecutive rays, claimed by whichever core is free:
  // misses cost more than returns (most leave the mapped box), so equal halves of the scan
  // took unequal times. Chunk c lists the usable rays it prepared, by End and in scan order,
  // in ends_[End][first_c, first_c + count[End]) (indices into rays_); merging drops the merged
  // ones in place, leaving the rays to trace.
  static constexpr int kChunks = 8;
  struct alignas(64) Chunk {            // aligned: chunks are written at the same time
    std::uint32_t first = 0, last = 0;  // its rays [first, last)
    std::array<std::uint32_t, 3> count{};
    std::uint64_t rays_outside = 0;
  };
  // What one half of a scan's tracing did (part 0 also counts the serial work on the slice).
  struct alignas(64) Part {  // aligned: the two halves write their own Part at the same time
    struct Resume {
      RayId ray = 0;
      std::uint8_t unchanged = 0, crossed = 0;  // the early-stop runs where the ray stopped
    };
    StaticVector<Resume, limits::kMaxLidarPoints> resume;  // rays that reached the slice
    std::uint64_t rays_merged = 0, voxel_updates = 0, voxel_visits = 0, misses_undone = 0;
    // The updates of the inferred miss being traced, until it reaches the sensor or a voxel
    // occupied now (see Mapper::trace). A ray that would update more voxels stops lowering them
    // at the limit.
    struct Undo {
      std::uint32_t voxel;
      std::int8_t logodds;
    };
    std::array<Undo, limits::kMaxRayUndo> undo;
  };
  struct Runs {
    int unchanged = 0, crossed = 0;
  };
  void prepare(const Pose3& sensor, const hal::LidarScanView& scan, int top_layers, Cut cut,
               Chunk& chunk);
  // The rays of chunk c that end in `end` (a view into ends_; after prepare).
  std::span<RayId> ends_of(End end, const Chunk& c) {
    return {ends_[end].data() + c.first, c.count[end]};
  }
  // Clears the bits of the layers below `top_layers` that the rays of this scan can reach.
  void clear_bits(Bits& bits, int top_layers, int row_lo, int row_hi) const;
  // Merges the rays that end in `end` by end voxel and applies their hits.
  void merge_and_hit(End end, Part& part, Bits& bits);
  void trace_half(const Vec3& origin, Cut cut, int side, Part& part, Bits& bits);
  // Back-traces a->b (a is the ray's end side), stopping in front of `stop`; false if an early
  // stop ended it.
  bool trace(const Vec3& a, const Vec3& b, VoxelLayer stop, bool first_is_end, bool hit, bool weak,
             Runs& runs, Part& part, Bits& bits);
  // Sets voxel i's per-scan bit and adds `delta` to its log-odds, clamped to [lo, hi]; true if
  // the log-odds changed.
  static bool add_once(std::int8_t* logodds, std::uint64_t* touched, std::size_t i, int delta,
                       int lo, int hi);
  // Runs part(0) .. part(parts - 1), at the same time when the platform gave us a fork-join.
  template <class F>
  void in_parts(int parts, F&& part);

  MapperConfig config_;
  ForkJoin* fork_join_;
  GridGeometry3d geometry_ = kWorldGrid3d;
  int reach_;  // voxels a ray can reach from the sensor's along x or y (max range + margin)
  std::int8_t hit_, miss_, weak_miss_, min_, max_, occupied_;
  MapperCounters counters_;
  std::array<std::int8_t, limits::kGridCells3d> logodds_;
  std::array<Bits, 2> bits_;                         // half k's; the slice uses half 0's
  StaticVector<Ray, limits::kMaxLidarPoints> rays_;  // the scan being inserted
  std::array<Chunk, kChunks> chunks_;
  std::array<std::array<RayId, limits::kMaxLidarPoints>, 3> ends_;  // see Chunk
  std::array<Part, 2> parts_;
  Vec3 last_sensor_ = Vec3::Zero();  // where the previous scan was taken
  int last_axis_ = 1;
};

}  // namespace colag::uav
