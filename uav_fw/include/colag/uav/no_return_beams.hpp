#pragma once
// A real LiDAR driver reports returns only: a beam that saw nothing within range is simply not
// in the scan. Free space along it is still worth knowing (the sky over a box field, the far
// side of an open square), and the sensor's pattern says which beams fired: every beam of the
// pattern without a return becomes a miss at maximum range, as the mapper expects them.
//
// What it cannot know: a beam lost on a dark or specular surface, or one that hit something
// closer than the sensor's minimum range. Two rules keep such a beam from opening a hole:
//   - a beam that points at the ground within its range cannot have seen nothing: its return was
//     lost (on whatever stands in front of the ground, a wall's foot as often as not), and
//     nothing is inferred from it. Traced to its maximum range, every such beam of every scan
//     ran through the lower part of whatever it had really hit: with 5 % of the returns lost,
//     a 0.2 m wall seen obliquely from 2 m lost its lower half in the UAV's map within a few
//     passes, and UGVs drove into it;
//   - the others (above the ground's horizon, within range of nothing) are counted by the mapper
//     as weaker evidence (MapperConfig::p_miss_inferred) that ends at the first occupied voxel on
//     its way and never lowers it.
// A surface within the minimum range (a metre) of the LiDAR is one the UAV's flight layer keeps
// it away from.
//
// A spinning LiDAR's pattern: beams at fixed elevations, fired in `columns` equal azimuth steps
// from the sensor's x axis. A pattern with no beams (a non-repetitive scanner, a pattern not
// configured) infers nothing.
#include <cstdint>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/hal/lidar.hpp"

namespace colag::uav {

struct LidarBeamPattern {
  int beams = 0;  // 0: unknown, nothing is inferred
  double lowest_elevation_deg = -25.2;
  double elevation_step_deg = 1.2;
  int columns = 1200;
};

// How far down the pattern looks everywhere around the UAV, mounted with `mount` on a level
// body: over all azimuths, the least steep of each azimuth's steepest beam (degrees, negative:
// down). Its blind disc on the ground is set by this beam. NaN for a pattern not known.
double blind_cone_elevation_deg(const LidarBeamPattern& pattern, const Quat& mount);

struct NoReturnCounters {
  std::uint64_t scans_completed = 0;
  std::uint64_t misses_inferred = 0;
  std::uint64_t returns_off_pattern = 0;  // between the beams' elevations: not binned
  std::uint64_t returns_lost = 0;         // beams without a return that point at the ground
};

class NoReturnBeams {
 public:
  // Allocates its tables here, never after. A pattern beyond the limits' beams x columns is
  // treated as unknown.
  explicit NoReturnBeams(const LidarBeamPattern& pattern = {});

  // The scan, taken from `sensor` (sensor frame -> map frame), with its no-return beams as
  // misses, but for those whose maximum range lies below the ground (the map frame's z =
  // `ground_z_m`). A scan that already lists misses, or one from an unknown pattern, is returned
  // as it is. The view is valid until the next call.
  hal::LidarScanView complete(const hal::LidarScanView& scan, const Pose3& sensor,
                              double ground_z_m);
  const NoReturnCounters& counters() const { return counters_; }
  bool knows_pattern() const { return pattern_.beams > 0; }

 private:
  LidarBeamPattern pattern_;
  std::vector<hal::LidarPoint> directions_;  // unit vector per (column, beam), column-major
  std::vector<std::uint8_t> returned_;       // per (column, beam), of the scan being completed
  std::vector<hal::LidarPoint> misses_;
  NoReturnCounters counters_;
};

}  // namespace colag::uav
