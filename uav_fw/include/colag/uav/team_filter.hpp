#pragma once
// The UAV's LiDAR sees the UGVs as well as the obstacles. A live UGV must not be mapped: it would
// stand in the map as an obstacle under itself (and stop), and leave ghosts behind it (its status
// keeps the others away from it, live). A UGV is *located* when its fresh status (estimator
// initialised) puts it at p to within u <= max_uncertainty_m (3 sigma). Then:
//   - returns above the ground layer and below body_top_m within r + margin + u of where it can be
//     now are dropped (its body, or something right beside it: no evidence either way). Where it
//     can be: from p along its heading as far as its reported speed takes it in the status's age
//     plus the link's latency (up to max_latency; the stamps of another board's clock do not
//     tell it): a capsule, not a disc, so a moving UGV is not mapped at its front;
//   - when it was not located at the previous scan (mission start, back from silence or from a
//     large uncertainty), what was mapped there is forgotten: it was its body;
//   - and so it is whenever the map holds a hit within body_radius - u of where it is: only its
//     body can be there (anything else would be a collision). Its body gets mapped when it was
//     located at the wrong place: a UGV initialised from an outlying relative pose 0.8 m off
//     stood beside its own body, mapped as an obstacle, waiting for support for 380 s;
// A UGV that is not located is mapped like any obstacle: a silent robot is in the way.
#include <bitset>
#include <cstdint>
#include <vector>

#include "colag/common/geometry.hpp"
#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/common/time.hpp"
#include "colag/hal/lidar.hpp"
#include "colag/uav/mapper.hpp"

namespace colag::uav {

struct TeamFilterConfig {
  double body_radius_m = 0.25;  // a UGV's footprint
  double margin_m = 0.15;       // the dropped disc: + this + the position's uncertainty
  double max_uncertainty_m = 0.5;
  double ground_top_m = 0.1;  // returns lower than this are the ground (kept)
  double body_top_m = 0.6;    // returns higher than this are not a UGV's
  Duration max_latency = std::chrono::milliseconds(500);  // of a status, on the link
  Duration max_age = std::chrono::seconds(1);             // an older status does not locate a UGV
};

struct TeamFilterCounters {
  std::uint64_t dropped = 0;    // returns dropped
  std::uint64_t located = 0;    // times a UGV's disc was forgotten: newly located, or own_body
  std::uint64_t own_body = 0;   // of those, a located UGV's own body found in the map
  std::uint64_t forgotten = 0;  // voxels forgotten then
};

class TeamFilter {
 public:
  explicit TeamFilter(const TeamFilterConfig& config = {});  // sizes its buffer once

  const TeamFilterConfig& config() const { return config_; }
  // Starts a scan's list of live UGVs.
  void begin();
  // UGV `id` reported at `where` (world) to within `uncertainty_m`, `age` ago, driving at
  // `speed_mps` along `yaw_rad`: located if the uncertainty is within max_uncertainty_m.
  // Returns whether it is.
  bool add(std::size_t id, const Vec2& where, double uncertainty_m, Duration age, double yaw_rad,
           double speed_mps);
  // Forgets in `map` the bodies of the UGVs located anew, and returns the scan without the
  // returns of the located UGVs. The view is valid until the next call.
  hal::LidarScanView apply(const hal::LidarScanView& scan, const Pose3& sensor, Mapper& map);
  const TeamFilterCounters& counters() const { return counters_; }

 private:
  struct Capsule {  // the points within `radius` of the segment [a, b]
    Vec2 a, b;
    double radius;
    double inner;  // within this of `a` only its body can be
    bool anew;
    Vec2 lo, hi;  // its bounding box: most returns are far from every UGV, and cheaply so
    bool contains(const Vec2& p) const;
  };
  TeamFilterConfig config_;
  StaticVector<Capsule, limits::kMaxUgvs> capsules_;
  std::bitset<limits::kMaxUgvs> located_, was_located_;
  std::vector<hal::LidarPoint> kept_;  // capacity kMaxLidarPoints, reserved at construction
  TeamFilterCounters counters_;
};

}  // namespace colag::uav
