#pragma once
// The field world's LiDAR errors: each return moved along its ray by range noise, some lost (dark
// or specular surfaces), and, as a real driver does, no list of the beams that saw nothing. Two
// random draws a return, ~14 000 returns a scan: in fixed chunks, each drawing from its own stream
// (seeded by the device, the scan and the chunk), so that they run on every core and the scan is
// the same whatever the number of cores.
#include <cstdint>
#include <span>

#include "colag/common/fork_join.hpp"
#include "colag/hal/lidar.hpp"

namespace colag::sim {

struct LidarErrors {
  double range_sigma_m = 0.0;  // Gaussian range noise of each return
  double dropout = 0.0;        // share of returns lost (dark or specular surfaces)
  bool returns_only = false;   // as a real driver: no list of the beams that saw nothing
  bool any() const { return range_sigma_m > 0.0 || dropout > 0.0 || returns_only; }
};

// Scan number `scan` of the device seeded `seed`: `points` with their errors into `out` (at least
// as long; the returns kept, in scan order), their number returned. `fork_join`: optional.
std::size_t add_lidar_errors(const LidarErrors& errors, std::uint64_t seed, std::uint64_t scan,
                             std::span<const hal::LidarPoint> points,
                             std::span<hal::LidarPoint> out, ForkJoin* fork_join);

}  // namespace colag::sim
