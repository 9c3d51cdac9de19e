#include "colag/sim/world/lidar_errors.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "colag/common/random.hpp"

namespace colag::sim {

std::size_t add_lidar_errors(const LidarErrors& errors, std::uint64_t seed, std::uint64_t scan,
                             std::span<const hal::LidarPoint> points,
                             std::span<hal::LidarPoint> out, ForkJoin* fork_join) {
  constexpr int kChunks = 8;
  const std::size_t n = std::min(points.size(), out.size());
  std::array<std::size_t, kChunks + 1> first{};  // chunk c: returns [first[c], first[c + 1])
  for (std::size_t c = 0; c <= kChunks; ++c)
    first[c] = n * c / kChunks;
  std::array<std::size_t, kChunks> kept{};
  const auto chunk = [&](int c) {
    const std::size_t from = first[static_cast<std::size_t>(c)];
    const std::size_t to = first[static_cast<std::size_t>(c) + 1];
    Rng rng(seed * 0x9E3779B97F4A7C15ULL + scan * kChunks + static_cast<std::uint64_t>(c));
    std::size_t o = from;
    for (std::size_t k = from; k < to; ++k) {
      const hal::LidarPoint& q = points[k];
      if (errors.dropout > 0.0 && rng.bernoulli(errors.dropout)) continue;
      const double r =
          std::sqrt(double{q.x_m} * q.x_m + double{q.y_m} * q.y_m + double{q.z_m} * q.z_m);
      const double noise =
          errors.range_sigma_m > 0.0 ? rng.gaussian(0.0, errors.range_sigma_m) : 0.0;
      const auto f = static_cast<float>(r > 0.0 ? std::max(r + noise, 0.0) / r : 1.0);
      out[o++] = {q.x_m * f, q.y_m * f, q.z_m * f};
    }
    kept[static_cast<std::size_t>(c)] = o - from;
  };
  if (fork_join != nullptr) {
    fork_join->run(kChunks, chunk);
  } else {
    for (int c = 0; c < kChunks; ++c)
      chunk(c);
  }
  std::size_t total = 0;  // the chunks' returns, closed up in scan order
  for (std::size_t c = 0; c < kChunks; ++c) {
    // Moved down (or not at all: std::copy may not copy a range onto itself).
    if (total != first[c]) {
      std::copy_n(out.begin() + static_cast<std::ptrdiff_t>(first[c]), kept[c],
                  out.begin() + static_cast<std::ptrdiff_t>(total));
    }
    total += kept[c];
  }
  return total;
}

}  // namespace colag::sim
