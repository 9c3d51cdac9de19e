#pragma once
// A simulated spinning LiDAR (VLP-32-like by default: 32 beams from -25.2 deg upward in
// 1.2 deg steps, 360 deg in `columns` steps, 8 m range, returns closer than 1 m dropped), ray
// cast against the box world and the ground plane z = 0. Returns are reported in the sensor
// frame; beams with no return within range are reported as misses at max range (so the mapper
// can clear free space along them). Boxes are culled per scan by range and (for a level
// sensor) azimuth, so a ray is tested only against the few boxes in its direction; a level
// sensor also cuts each of those boxes to its column once, for all the column's beams.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "colag/common/fork_join.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/sim/world/box_world.hpp"

namespace colag::sim {

struct LidarPattern {
  int beams = 32;
  double lowest_elevation_deg = -25.2;
  double elevation_step_deg = 1.2;
  int columns = 1200;  // 0.3 deg
  double max_range_m = 8.0;
  double min_range_m = 1.0;
};

class LidarSimulator {
 public:
  // `fork_join` (optional, not owned): cast the two halves of a turn on two cores.
  explicit LidarSimulator(const LidarPattern& pattern = {}, ForkJoin* fork_join = nullptr);

  // One full scan from `sensor` (sensor frame -> world). The spans stay valid until the next
  // call. Allocates nothing after construction.
  void scan(const BoxWorld& world, const Pose3& sensor, std::span<const hal::LidarPoint>& points,
            std::span<const hal::LidarPoint>& misses);
  const LidarPattern& pattern() const { return pattern_; }

 private:
  LidarPattern pattern_;
  ForkJoin* fork_join_;
  std::vector<Vec3> directions_;  // unit vectors in the sensor frame, column-major
  // A level sensor's beams share their column's horizontal direction (azimuth, per column) and
  // their elevation (per beam): a box is cut to the stretch of horizontal distance the column
  // crosses it over once per column, then each beam only checks its height over that stretch.
  std::vector<Vec2> azimuths_;  // (cos, sin) per column, sensor frame
  struct Elevation {
    double inv_cos, inv_tan, sin;  // inv_tan is 0 for a level beam
  };
  std::vector<Elevation> elevations_;  // per beam
  struct LevelBeam {
    double ground;  // distance to the ground along the beam (infinity if it never gets there)
    bool may_hit_a_box;
  };
  std::vector<LevelBeam> level_beams_;  // per beam, for the scan being cast (level sensor)
  struct Stretch {  // where a column's horizontal line crosses a box's footprint
    double s0, s1, base, height;
  };
  // The last scan, in column order; every buffer holds a whole turn (sized at construction).
  std::vector<hal::LidarPoint> points_, misses_;
  struct alignas(64) Part {  // one cache line each: the two parts write at the same time
    std::vector<hal::LidarPoint> points, misses;  // this part's columns, in order
    std::vector<Stretch> stretches;               // of the column being cast (level sensor)
  };
  std::array<Part, 2> parts_;
  std::vector<std::vector<int>> column_boxes_;  // per column: boxes that may be hit (level)
  std::vector<int> in_range_;                   // boxes within range (every column, tilted)
  struct ColumnCount {
    std::uint16_t points = 0, misses = 0;
  };
  std::vector<ColumnCount> column_counts_;  // per column, of the last scan
  static constexpr int kBlock = 16;         // columns cast together by one part
};

// A ray set up for testing against many boxes: the inverse of its direction per axis, so a
// box test multiplies instead of dividing.
struct BoxRay {
  BoxRay(const Vec3& origin, const Vec3& dir);
  Vec3 origin, inv_dir;
  std::array<bool, 3> parallel;  // no direction along this axis (inv_dir unused)
};

// Distance along the ray (origin, unit direction) to the box, or a negative value if missed.
double ray_box(const BoxRay& ray, const Box& box);
inline double ray_box(const Vec3& origin, const Vec3& dir, const Box& box) {
  return ray_box(BoxRay(origin, dir), box);
}

}  // namespace colag::sim
