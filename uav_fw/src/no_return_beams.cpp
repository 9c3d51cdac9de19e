#include "colag/uav/no_return_beams.hpp"

#include <algorithm>
#include <cmath>

#include "colag/common/fast_atan2.hpp"
#include "colag/common/limits.hpp"

namespace colag::uav {

double blind_cone_elevation_deg(const LidarBeamPattern& pattern, const Quat& mount) {
  if (pattern.beams <= 0 || !(pattern.elevation_step_deg > 0.0)) return std::nan("");
  // Sampled every degree of the sensor's azimuth: a mount tilted by a few degrees moves the
  // steepest beam's elevation by less than the sampling misses.
  constexpr int kAzimuths = 360;
  double least_steep = -90.0;
  for (int a = 0; a < kAzimuths; ++a) {
    const double az = 2.0 * M_PI * a / kAzimuths;
    double steepest = 90.0;
    for (int b = 0; b < pattern.beams; ++b) {
      const double el =
          (pattern.lowest_elevation_deg + b * pattern.elevation_step_deg) * M_PI / 180.0;
      const Vec3 d =
          mount * Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      steepest = std::min(steepest, std::asin(std::clamp(d.z(), -1.0, 1.0)) * 180.0 / M_PI);
    }
    least_steep = std::max(least_steep, steepest);
  }
  return least_steep;
}

NoReturnBeams::NoReturnBeams(const LidarBeamPattern& pattern) : pattern_(pattern) {
  const bool fits = pattern.beams > 0 && pattern.columns > 0 &&
                    static_cast<std::size_t>(pattern.beams) <= limits::kMaxLidarBeams &&
                    static_cast<std::size_t>(pattern.columns) <= limits::kMaxLidarColumns &&
                    pattern.elevation_step_deg > 0.0;
  if (!fits) {
    pattern_.beams = 0;
    return;
  }
  const auto n =
      static_cast<std::size_t>(pattern.beams) * static_cast<std::size_t>(pattern.columns);
  directions_.reserve(n);
  for (int c = 0; c < pattern.columns; ++c) {
    const double az = 2.0 * M_PI * c / pattern.columns;
    for (int b = 0; b < pattern.beams; ++b) {
      const double el =
          (pattern.lowest_elevation_deg + b * pattern.elevation_step_deg) * M_PI / 180.0;
      directions_.push_back({static_cast<float>(std::cos(el) * std::cos(az)),
                             static_cast<float>(std::cos(el) * std::sin(az)),
                             static_cast<float>(std::sin(el))});
    }
  }
  returned_.assign(n, 0);
  misses_.reserve(n);
}

hal::LidarScanView NoReturnBeams::complete(const hal::LidarScanView& scan, const Pose3& sensor,
                                           double ground_z_m) {
  if (pattern_.beams == 0 || !scan.misses.empty() || !(scan.max_range_m > 0.0F)) return scan;
  std::fill(returned_.begin(), returned_.end(), std::uint8_t{0});
  const double to_beam = 1.0 / pattern_.elevation_step_deg;
  const double to_column = pattern_.columns / (2.0 * M_PI);
  for (const hal::LidarPoint& p : scan.points) {
    // Floats squared in double cannot overflow: no need for hypot's care (nor its cost).
    const double x = p.x_m, y = p.y_m;
    const double horizontal = std::sqrt(x * x + y * y);
    const double el_deg = fast_atan2(double{p.z_m}, horizontal) * (180.0 / M_PI);
    const double b = (el_deg - pattern_.lowest_elevation_deg) * to_beam;
    // The nearest beam, rounded by truncating b + 1/2 (std::round is a libm call on x86-64's
    // baseline, 2 % of a field mission's time): below beam 0 or past the last (or not finite),
    // or half a step off every beam: not a beam of this pattern.
    const double up = b + 0.5;
    const bool on_pattern = up >= 0.0 && up < pattern_.beams &&
                            std::abs(b - static_cast<double>(static_cast<int>(up))) <= 0.25;
    if (!on_pattern) {
      ++counters_.returns_off_pattern;
      continue;
    }
    const auto bi = static_cast<std::size_t>(up);
    double az = fast_atan2(y, x);
    if (az < 0.0) az += 2.0 * M_PI;
    const double column_up = az * to_column + 0.5;  // >= 0: truncating it rounds, as for b
    const int c = static_cast<int>(column_up) % pattern_.columns;
    returned_[static_cast<std::size_t>(c) * static_cast<std::size_t>(pattern_.beams) + bi] = 1;
  }
  misses_.clear();
  const float r = scan.max_range_m;
  // A beam's height at its maximum range: the sensor's, plus the range times its direction's z
  // in the map frame (the rotation's last row).
  const Vec3 up = sensor.q.toRotationMatrix().row(2).transpose() * double{r};
  const double lowest_end = ground_z_m - sensor.p.z();
  std::uint64_t lost = 0;
  for (std::size_t k = 0; k < returned_.size(); ++k) {
    if (returned_[k] != 0) continue;
    const hal::LidarPoint& d = directions_[k];
    if (up.x() * d.x_m + up.y() * d.y_m + up.z() * d.z_m < lowest_end) {
      ++lost;
      continue;
    }
    misses_.push_back({d.x_m * r, d.y_m * r, d.z_m * r});
  }
  counters_.returns_lost += lost;
  ++counters_.scans_completed;
  counters_.misses_inferred += misses_.size();
  hal::LidarScanView out = scan;
  out.misses = misses_;
  out.misses_inferred = true;
  return out;
}

}  // namespace colag::uav
