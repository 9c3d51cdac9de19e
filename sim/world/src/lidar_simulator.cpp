#include "colag/sim/world/lidar_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colag::sim {

BoxRay::BoxRay(const Vec3& o, const Vec3& d) : origin(o), inv_dir(Vec3::Zero()) {
  for (int a = 0; a < 3; ++a) {
    parallel[static_cast<std::size_t>(a)] = std::abs(d[a]) < 1e-12;
    if (!parallel[static_cast<std::size_t>(a)]) inv_dir[a] = 1.0 / d[a];
  }
}

double ray_box(const BoxRay& ray, const Box& b) {
  const Vec3 lo(b.center.x() - b.half_size.x(), b.center.y() - b.half_size.y(), b.base_m);
  const Vec3 hi(b.center.x() + b.half_size.x(), b.center.y() + b.half_size.y(), b.height_m);
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  // Height first: most beams that miss pass above the boxes.
  for (const int a : {2, 0, 1}) {
    const double o = ray.origin[a];
    if (ray.parallel[static_cast<std::size_t>(a)]) {
      if (o < lo[a] || o > hi[a]) return -1.0;
      continue;
    }
    double ta = (lo[a] - o) * ray.inv_dir[a], tb = (hi[a] - o) * ray.inv_dir[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return -1.0;
  }
  return t0;
}

LidarSimulator::LidarSimulator(const LidarPattern& pattern, ForkJoin* fork_join)
    : pattern_(pattern), fork_join_(fork_join) {
  const std::size_t n =
      static_cast<std::size_t>(pattern.beams) * static_cast<std::size_t>(pattern.columns);
  // One formula for a beam's elevation: the level path relies on elevations_[b].sin being the
  // very value in every column's direction of beam b.
  const auto elevation = [&](int b) {
    return (pattern.lowest_elevation_deg + b * pattern.elevation_step_deg) * M_PI / 180.0;
  };
  directions_.reserve(n);
  for (int c = 0; c < pattern.columns; ++c) {
    const double az = 2.0 * M_PI * c / pattern.columns;
    azimuths_.emplace_back(std::cos(az), std::sin(az));
    for (int b = 0; b < pattern.beams; ++b) {
      const double el = elevation(b);
      directions_.emplace_back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                               std::sin(el));
    }
  }
  for (int b = 0; b < pattern.beams; ++b) {
    const double el = elevation(b);
    const double tan = std::tan(el);
    // Within 1e-12 of level counts as level, as a 3-D slab test treats a parallel axis.
    elevations_.push_back(
        {1.0 / std::cos(el), std::abs(tan) < 1e-12 ? 0.0 : 1.0 / tan, std::sin(el)});
  }
  // Fixed buffers, sized once: a scan fills them from the start (push_back kept the vector's end
  // in memory, a load and a store per beam the next beam waited for).
  points_.resize(n);
  misses_.resize(n);
  for (std::size_t part = 0; part < 2; ++part) {
    parts_[part].points.resize(n);
    parts_[part].misses.resize(n);
    parts_[part].stretches.reserve(256);
  }
  level_beams_.resize(static_cast<std::size_t>(pattern.beams));
  column_boxes_.resize(static_cast<std::size_t>(pattern.columns));
  column_counts_.resize(static_cast<std::size_t>(pattern.columns));
  in_range_.reserve(256);
  for (auto& c : column_boxes_)
    c.reserve(64);
}

void LidarSimulator::scan(const BoxWorld& world, const Pose3& sensor,
                          std::span<const hal::LidarPoint>& points,
                          std::span<const hal::LidarPoint>& misses) {
  const double range = pattern_.max_range_m;
  const Mat3 R = sensor.q.toRotationMatrix();
  const double yaw = yaw_of(sensor.q);
  // Cull: boxes within range, entered in every column their azimuth span covers (in the
  // sensor's heading frame). Only for a level sensor (exactly: no roll, no pitch): tilted, a
  // beam's azimuth in the world depends on its elevation too, so every column tests every box
  // within range.
  const bool level = R(2, 0) == 0.0 && R(2, 1) == 0.0;
  for (auto& c : column_boxes_)
    c.clear();
  in_range_.clear();
  const int cols = pattern_.columns;
  double top = -std::numeric_limits<double>::infinity();  // of the boxes within range
  for (std::size_t i = 0; i < world.boxes.size(); ++i) {
    const Box& b = world.boxes[i];
    const Vec2 rel = b.center - sensor.p.head<2>();
    const double reach = b.half_size.norm();
    const double dist = rel.norm();
    if (dist - reach > range) continue;
    top = std::max(top, b.height_m);
    in_range_.push_back(static_cast<int>(i));
    if (!level) continue;
    int c0 = 0, c1 = cols - 1;
    if (dist > reach + 1e-6) {
      const double centre = std::atan2(rel.y(), rel.x()) - yaw;
      const double half = std::asin(std::min(1.0, reach / dist)) + 2.0 * M_PI / cols;
      c0 = static_cast<int>(std::floor((centre - half) / (2.0 * M_PI) * cols));
      c1 = static_cast<int>(std::ceil((centre + half) / (2.0 * M_PI) * cols));
    }
    for (int c = c0; c <= c1 && c - c0 < cols; ++c) {
      column_boxes_[static_cast<std::size_t>(((c % cols) + cols) % cols)].push_back(
          static_cast<int>(i));
    }
  }
  // A beam that stays above every box within range cannot hit one: most of those pointing
  // up or near level, from a UAV flying above the boxes.
  const double above = sensor.p.z() - top;
  const auto may_hit_a_box = [&](double dir_z) { return above <= 0.0 || -dir_z * range >= above; };
  const auto ground = [&](double dir_z) {
    return dir_z < -1e-9 ? -sensor.p.z() / dir_z : std::numeric_limits<double>::infinity();
  };
  // Level, a beam's world direction rises as in the sensor frame in every column (R's last row
  // is (0, 0, r22)): its ground distance and whether it may reach a box are per beam.
  if (level) {
    for (int b = 0; b < pattern_.beams; ++b) {
      const double dir_z = R(2, 2) * elevations_[static_cast<std::size_t>(b)].sin;
      level_beams_[static_cast<std::size_t>(b)] = {ground(dir_z), may_hit_a_box(dir_z)};
    }
  }
  // A level sensor: each candidate box cut to the stretch [s0, s1] of horizontal distance
  // along the column's direction `h` that lies over its footprint (none if it misses or lies
  // beyond range: a beam goes at least as far as its horizontal distance).
  const Vec3& p = sensor.p;
  const auto cut_to_column = [&](const Vec2& h, const std::vector<int>& candidates,
                                 std::vector<Stretch>& out) {
    out.clear();
    for (const int i : candidates) {
      const Box& b = world.boxes[static_cast<std::size_t>(i)];
      double s0 = 0.0, s1 = range;
      for (int a = 0; a < 2; ++a) {
        const double lo = b.center[a] - b.half_size[a], hi = b.center[a] + b.half_size[a];
        if (std::abs(h[a]) < 1e-12) {
          if (p[a] < lo || p[a] > hi) s1 = -1.0;
          continue;
        }
        const double inv = 1.0 / h[a];
        const double sa = (lo - p[a]) * inv, sb = (hi - p[a]) * inv;
        s0 = std::max(s0, std::min(sa, sb));
        s1 = std::min(s1, std::max(sa, sb));
      }
      if (s0 <= s1) out.push_back({s0, s1, b.base_m, b.height_m});
    }
  };
  // The nearest box a beam of elevation `e` hits within the column's stretches, as a distance
  // along the beam (infinity if none): where its height is within the box's over the stretch.
  const auto nearest_box = [&](const Elevation& e, const std::vector<Stretch>& stretches) {
    double t = std::numeric_limits<double>::infinity();
    for (const Stretch& st : stretches) {
      double s0 = st.s0, s1 = st.s1;
      if (e.inv_tan == 0.0) {
        if (p.z() < st.base || p.z() > st.height) continue;
      } else {
        const double sa = (st.base - p.z()) * e.inv_tan, sb = (st.height - p.z()) * e.inv_tan;
        s0 = std::max(s0, std::min(sa, sb));
        s1 = std::min(s1, std::max(sa, sb));
      }
      if (s0 <= s1) t = std::min(t, s0 * e.inv_cos);
    }
    return t;
  };
  // Cast the turn in blocks of columns, even blocks in part 0 and odd ones in part 1 (at the
  // same time when there is a fork-join: boxes crowd some directions, so halves of the turn
  // would take unequal times), then join them in column order: the same scan either way.
  const auto cast = [&](int part) {
    auto& [pts, mis, stretches] = parts_[static_cast<std::size_t>(part)];
    std::size_t n_pts = 0, n_mis = 0;
    for (int c0 = part * kBlock; c0 < cols; c0 += 2 * kBlock) {
      for (int c = c0; c < std::min(c0 + kBlock, cols); ++c) {
        const auto& candidates = level ? column_boxes_[static_cast<std::size_t>(c)] : in_range_;
        if (level) {
          const Vec2& az = azimuths_[static_cast<std::size_t>(c)];
          cut_to_column(R.topLeftCorner<2, 2>() * az, candidates, stretches);
        }
        const std::size_t pts0 = n_pts, mis0 = n_mis;
        for (int b = 0; b < pattern_.beams; ++b) {
          const Vec3& local = directions_[static_cast<std::size_t>(c) * pattern_.beams + b];
          double t = 0.0;  // to the nearest of the ground and the boxes
          if (level) {
            const LevelBeam& beam = level_beams_[static_cast<std::size_t>(b)];
            t = beam.ground;
            if (!stretches.empty() && beam.may_hit_a_box) {
              t = std::min(t, nearest_box(elevations_[static_cast<std::size_t>(b)], stretches));
            }
          } else {
            const Vec3 dir = R * local;
            t = ground(dir.z());
            if (!candidates.empty() && may_hit_a_box(dir.z())) {
              const BoxRay ray(sensor.p, dir);
              for (const int i : candidates) {
                const double tb = ray_box(ray, world.boxes[static_cast<std::size_t>(i)]);
                if (tb >= 0.0 && tb < t) t = tb;
              }
            }
          }
          if (t < pattern_.min_range_m) continue;  // too close: the sensor reports nothing
          const Vec3 end = local * std::min(t, range);
          const hal::LidarPoint point{static_cast<float>(end.x()), static_cast<float>(end.y()),
                                      static_cast<float>(end.z())};
          if (t <= range) {
            pts[n_pts++] = point;
          } else {
            mis[n_mis++] = point;
          }
        }
        column_counts_[static_cast<std::size_t>(c)] = {static_cast<std::uint16_t>(n_pts - pts0),
                                                       static_cast<std::uint16_t>(n_mis - mis0)};
      }
    }
  };
  if (fork_join_ != nullptr) {
    fork_join_->run(2, cast);
  } else {
    cast(0);
    cast(1);
  }
  std::array<std::size_t, 2> next_point{}, next_miss{};
  std::size_t n_points = 0, n_misses = 0;
  for (int c = 0; c < cols; ++c) {
    const std::size_t part = static_cast<std::size_t>((c / kBlock) % 2);
    const auto [column_points, column_misses] = column_counts_[static_cast<std::size_t>(c)];
    const Part& from = parts_[part];
    std::copy_n(from.points.begin() + static_cast<std::ptrdiff_t>(next_point[part]), column_points,
                points_.begin() + static_cast<std::ptrdiff_t>(n_points));
    std::copy_n(from.misses.begin() + static_cast<std::ptrdiff_t>(next_miss[part]), column_misses,
                misses_.begin() + static_cast<std::ptrdiff_t>(n_misses));
    next_point[part] += column_points;
    next_miss[part] += column_misses;
    n_points += column_points;
    n_misses += column_misses;
  }
  points = {points_.data(), n_points};
  misses = {misses_.data(), n_misses};
}

}  // namespace colag::sim
