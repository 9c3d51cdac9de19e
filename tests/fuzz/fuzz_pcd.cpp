// PCD files as colag_sim --map loads them: parse_pcd on arbitrary bytes, then the obstacle
// extraction. Invariants: a parse either fails with a message or yields finite points; every box
// is well-formed.
#include <cmath>
#include <string>
#include <vector>

#include "colag/sim/world/cloud_world.hpp"
#include "colag/sim/world/pcd_loader.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::vector<colag::Vec3> points;
  std::string error;
  if (!colag::sim::parse_pcd(bytes, points, error)) {
    COLAG_FUZZ_CHECK(!error.empty());
    return 0;
  }
  for (const auto& p : points)
    COLAG_FUZZ_CHECK(p.allFinite());
  const colag::sim::BoxWorld world = colag::sim::box_world_from_points(points);
  for (const auto& b : world.boxes) {
    COLAG_FUZZ_CHECK(b.center.allFinite() && b.half_size.allFinite() && std::isfinite(b.height_m));
    COLAG_FUZZ_CHECK(b.half_size.x() > 0.0 && b.half_size.y() > 0.0 && b.height_m > 0.0);
  }
  return 0;
}
