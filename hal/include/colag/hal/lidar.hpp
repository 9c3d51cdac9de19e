#pragma once
#include <cstddef>
#include <span>

#include "colag/common/time.hpp"

namespace colag::hal {

struct LidarPoint {
  float x_m, y_m, z_m;  // sensor frame
};

// A complete scan. The points belong to the driver and stay valid until the next poll().
struct LidarScanView {
  TimePoint stamp;
  float max_range_m = 0.0F;
  std::span<const LidarPoint> points;  // returns only (no-return beams are absent)
  // Beams without a return: their end points at max range, so the mapper can clear free space.
  std::span<const LidarPoint> misses;
  // The misses are inferred from the sensor's pattern (a beam with no return), not reported by
  // it: the beam may have been lost on a dark surface, so they are weaker evidence.
  bool misses_inferred = false;
};

class Lidar {
 public:
  virtual ~Lidar() = default;
  // True when a new scan is available; `out` then views it.
  virtual bool poll(LidarScanView& out) = 0;
};

}  // namespace colag::hal
