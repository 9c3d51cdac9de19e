#include "colag/sim/world/pcd_writer.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

namespace colag::sim {

namespace {
constexpr double kStep_m = 0.1;
constexpr double kGroundMargin_m = 3.5;  // the paper's maps: a 27 m arena on a 35 m ground

// Grid lines from `lo` to `hi` inclusive, at whole multiples of the step (no drift).
std::vector<double> steps(double lo, double hi) {
  std::vector<double> v;
  for (long k = std::lround(std::ceil(lo / kStep_m - 1e-9));
       static_cast<double>(k) * kStep_m <= hi + 1e-9; ++k)
    v.push_back(static_cast<double>(k) * kStep_m);
  return v;
}
}  // namespace

std::string to_pcd(const BoxWorld& world) {
  std::string body;
  std::size_t n = 0;
  char line[96];
  const auto point = [&](double x, double y, double z) {
    std::snprintf(line, sizeof line, "%.2f %.2f %.1f\n", x, y, z);
    body += line;
    ++n;
  };
  for (const double y : steps(world.min_y_m - kGroundMargin_m, world.max_y_m + kGroundMargin_m))
    for (const double x : steps(world.min_x_m - kGroundMargin_m, world.max_x_m + kGroundMargin_m))
      point(x, y, 0.0);
  for (const Box& b : world.boxes) {
    // The points at the centres of the 0.1 m cells the footprint covers.
    const Vec2 lo = b.center - b.half_size;
    const long nx = std::lround(2.0 * b.half_size.x() / kStep_m);
    const long ny = std::lround(2.0 * b.half_size.y() / kStep_m);
    // Every 0.1 m from just above the ground (or from its base) up to its top.
    const long k0 = b.base_m > 0.0 ? std::lround(std::ceil(b.base_m / kStep_m - 1e-9)) : 1;
    const long nz = std::lround(b.height_m / kStep_m);
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i)
        for (long k = k0; k <= nz; ++k)
          point(lo.x() + (static_cast<double>(i) + 0.5) * kStep_m,
                lo.y() + (static_cast<double>(j) + 0.5) * kStep_m,
                static_cast<double>(k) * kStep_m);
  }
  char header[256];
  std::snprintf(header, sizeof header,
                "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n"
                "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH %zu\nHEIGHT 1\n"
                "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS %zu\nDATA ascii\n",
                n, n);
  return header + body;
}

bool save_pcd(const std::string& path, const BoxWorld& world, std::string& error) {
  std::ofstream out(path);
  out << to_pcd(world);
  if (!out.flush()) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

}  // namespace colag::sim
