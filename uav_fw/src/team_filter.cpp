#include "colag/uav/team_filter.hpp"

#include <algorithm>
#include <cmath>

namespace colag::uav {

bool TeamFilter::Capsule::contains(const Vec2& p) const {
  const Vec2 ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double t = len_sq > 0.0 ? std::clamp((p - a).dot(ab) / len_sq, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).squaredNorm() <= radius * radius;
}

TeamFilter::TeamFilter(const TeamFilterConfig& config) : config_(config) {
  kept_.reserve(limits::kMaxLidarPoints);
}

void TeamFilter::begin() {
  was_located_ = located_;
  located_.reset();
  capsules_.clear();
}

bool TeamFilter::add(std::size_t id, const Vec2& where, double uncertainty_m, Duration age,
                     double yaw_rad, double speed_mps) {
  if (id >= limits::kMaxUgvs || located_.test(id) || !all_finite(where) ||
      !std::isfinite(yaw_rad) || !std::isfinite(speed_mps) || !(uncertainty_m >= 0.0) ||
      uncertainty_m > config_.max_uncertainty_m || age > config_.max_age) {
    return false;
  }
  located_.set(id);
  const double travel_s = std::max(to_seconds(age + config_.max_latency), 0.0);
  const Vec2 to = where + speed_mps * travel_s * Vec2(std::cos(yaw_rad), std::sin(yaw_rad));
  const double r = config_.body_radius_m + config_.margin_m + uncertainty_m;
  const Vec2 pad(r, r);
  (void)capsules_.push_back({where, to, r, config_.body_radius_m - uncertainty_m,
                             !was_located_.test(id), where.cwiseMin(to) - pad,
                             where.cwiseMax(to) + pad});
  return true;
}

hal::LidarScanView TeamFilter::apply(const hal::LidarScanView& scan, const Pose3& sensor,
                                     Mapper& map) {
  if (capsules_.empty()) return scan;
  for (Capsule& c : capsules_) {
    if (!c.anew && c.inner > 0.0 &&
        map.count_hit(c.a, c.inner, config_.ground_top_m, config_.body_top_m) > 0) {
      ++counters_.own_body;
      c.anew = true;
    }
    if (!c.anew) continue;
    ++counters_.located;
    counters_.forgotten += map.forget(0.5 * (c.a + c.b), c.radius + 0.5 * (c.b - c.a).norm(),
                                      config_.ground_top_m, config_.body_top_m);
  }
  const Mat3 R = sensor.q.toRotationMatrix();
  kept_.clear();
  for (const hal::LidarPoint& p : scan.points) {
    const Vec3 w = R * Vec3(p.x_m, p.y_m, p.z_m) + sensor.p;
    bool team = false;
    if (w.z() >= config_.ground_top_m && w.z() <= config_.body_top_m) {
      for (const Capsule& c : capsules_) {
        if (w.x() < c.lo.x() || w.x() > c.hi.x() || w.y() < c.lo.y() || w.y() > c.hi.y()) continue;
        if (c.contains(w.head<2>())) {
          team = true;
          break;
        }
      }
    }
    if (team) {
      ++counters_.dropped;
    } else {
      kept_.push_back(p);  // within the capacity reserved: a scan has at most that many
    }
  }
  hal::LidarScanView out = scan;
  out.points = kept_;
  return out;
}

}  // namespace colag::uav
