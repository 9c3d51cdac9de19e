#include "colag/sim/mission/map_checks.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "colag/sim/mission/mission_config.hpp"
#include "colag/sim/world/ugv_body.hpp"

namespace colag::mission {

namespace {
constexpr double kMaxSite_m = 1000.0;  // wider than this: not metres
}  // namespace

bool check_map(const sim::BoxWorld& world, const sim::CloudWorldReport& report,
               const MissionConfig& cfg, std::vector<std::string>& warnings, std::string& error) {
  const int ugvs = cfg.ugvs;
  char text[320];
  const Vec2 lo(world.min_x_m, world.min_y_m), hi(world.max_x_m, world.max_y_m);
  if (report.extent_m.maxCoeff() > kMaxSite_m) {
    std::snprintf(text, sizeof text,
                  "the map spans %.0f x %.0f: wider than %.0f m, it is not in metres "
                  "(millimetres?); convert it to metres",
                  report.extent_m.x(), report.extent_m.y(), kMaxSite_m);
    error = text;
    return false;
  }
  const sim::UgvBodyConfig body;
  const auto inside_map = [&](const Vec2& p) {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  };
  for (int i = 0; i < ugvs; ++i) {
    std::vector<std::pair<std::string, Vec2>> points{{"start", ugv_start(cfg, i).p},
                                                     {"goal", ugv_goal(cfg, i)}};
    for (std::size_t k = 0; k < ugv_via(cfg, i).size(); ++k)
      points.emplace_back("via point " + std::to_string(k), ugv_via(cfg, i)[k]);
    for (const auto& [what, p] : points) {
      if (!inside_map(p)) {
        std::snprintf(text, sizeof text,
                      "UGV %d's %s (%.1f, %.1f) lies outside the map (x %.1f..%.1f, y "
                      "%.1f..%.1f): %s; is the map shifted?",
                      i, what.c_str(), p.x(), p.y(), lo.x(), hi.x(), lo.y(), hi.y(),
                      cfg.placements.empty()
                          ? "the layout puts starts at y = 16 and goals at y = -16 about the origin"
                          : "as the scenario places it");
        error = text;
        return false;
      }
      if (world.clearance(p, body.band_low_m, body.band_high_m) < body.radius_m) {
        std::snprintf(text, sizeof text,
                      "UGV %d's %s (%.2f, %.2f) is inside or touching an obstacle: it %s", i,
                      what.c_str(), p.x(), p.y(),
                      what == "start"  ? "starts in a collision"
                      : what == "goal" ? "cannot reach its goal"
                                       : "cannot pass it");
        warnings.emplace_back(text);
      }
    }
  }
  // The area the UGVs cross: the box around every start and goal, plus a body.
  Vec2 c_lo = ugv_start(cfg, 0).p, c_hi = c_lo;
  for (int i = 0; i < ugvs; ++i) {
    for (const Vec2& p : {ugv_start(cfg, i).p, ugv_goal(cfg, i)}) {
      c_lo = c_lo.cwiseMin(p);
      c_hi = c_hi.cwiseMax(p);
    }
  }
  c_lo -= Vec2(1.0, 0.0);
  c_hi += Vec2(1.0, 0.0);
  const bool any = std::any_of(world.boxes.begin(), world.boxes.end(), [&](const sim::Box& b) {
    const Vec2 b_lo = b.center - b.half_size, b_hi = b.center + b.half_size;
    return b.reaches(body.band_low_m, body.band_high_m) && (b_hi.array() >= c_lo.array()).all() &&
           (b_lo.array() <= c_hi.array()).all();
  });
  if (!any) {
    warnings.emplace_back(
        "no obstacle lies between the starts and the goals: the UGVs cross an empty arena");
  }
  if (std::abs(report.ground.z_m) > 0.02 || report.ground.sigma_m > 0.01) {
    std::snprintf(text, sizeof text,
                  "the ground was fitted at z = %.3f m (noise %.3f m): heights are taken from it; "
                  "%zu columns of clutter lower than %.2f m above it were dropped",
                  report.ground.z_m, report.ground.sigma_m, report.clutter_columns,
                  body.band_low_m);
    warnings.emplace_back(text);
  }
  return true;
}

}  // namespace colag::mission
