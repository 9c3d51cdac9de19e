#include "colag/sim/mission/mission_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "colag/common/limits.hpp"
#include "colag/sim/mission/map_checks.hpp"
#include "colag/sim/world/cloud_world.hpp"
#include "colag/sim/world/pcd_loader.hpp"

namespace colag::mission {

const char* to_string(Ablation a) {
  switch (a) {
    case Ablation::kNone:
      return "none";
    case Ablation::kNoRpe:
      return "no-rpe";
    case Ablation::kNoUncertainty:
      return "no-uncertainty";
    case Ablation::kNoScheduling:
      return "no-scheduling";
    case Ablation::kNoTimeWindows:
      return "no-time-windows";
  }
  return "?";
}

bool parse_window(const std::string& s, TimeWindow& out) {
  const auto colon = s.find(':');
  if (colon == std::string::npos) return false;
  char* end = nullptr;
  const std::string a = s.substr(0, colon), b = s.substr(colon + 1);
  const double from = std::strtod(a.c_str(), &end);
  if (a.empty() || *end != '\0') return false;
  const double to = std::strtod(b.c_str(), &end);
  if (b.empty() || *end != '\0' || !(from >= 0.0) || !(to > from)) return false;
  out = {from, to};
  return true;
}

bool parse_kill(const std::string& s, int& ugv, double& at_s) {
  const auto at = s.find('@');
  if (at == std::string::npos || at == 0 || at + 1 == s.size()) return false;
  const std::string a = s.substr(0, at), b = s.substr(at + 1);
  if (a.find_first_not_of("0123456789") != std::string::npos || a.size() > 6) return false;
  char* end = nullptr;
  const double t = std::strtod(b.c_str(), &end);
  if (*end != '\0' || !(t > 0.0) || !(t <= 1e6)) return false;
  ugv = std::stoi(a);
  at_s = t;
  return true;
}

bool parse_ablation(const std::string& s, Ablation& out) {
  for (Ablation a : {Ablation::kNone, Ablation::kNoRpe, Ablation::kNoUncertainty,
                     Ablation::kNoScheduling, Ablation::kNoTimeWindows}) {
    if (s == to_string(a)) {
      out = a;
      return true;
    }
  }
  return false;
}

namespace {

const Vec3 kUavStart{0.0, 15.0, 1.0};
constexpr int kPaperLanes = 17;  // x = 0, -2, 2, ..., -16, 16

// UGV i's lane. The paper's layout: x = 0, -2, 2, -4, 4, ... from y = 16 to y = -16. A larger
// fleet fills the odd lanes x = -1, 1, -3, 3, ... in a second row behind the first, from
// y = 18 to y = -18 (it drives between the first row's UGVs at the start and the goal).
double lane_x(int i) {
  // NOLINTBEGIN(bugprone-integer-division): lane numbers
  if (i < kPaperLanes) return (i % 2 == 1 ? -2.0 : 2.0) * ((i + 1) / 2);
  const int k = i - kPaperLanes;
  return (k % 2 == 0 ? -1.0 : 1.0) * (2 * (k / 2) + 1);
  // NOLINTEND(bugprone-integer-division)
}
double start_y(int i) {
  return i < kPaperLanes ? 16.0 : 18.0;
}

// A generated site's field: the whole width, its length less kSiteEndBand_m at each end (where
// the UGVs start and arrive, kSiteStartInset_m from the site's edge, as in the paper's layout).
constexpr double kSiteEndBand_m = 5.0;
constexpr double kSiteStartInset_m = 2.5;
constexpr double kPaperArenaSide_m = 27.0;

}  // namespace

bool has_site(const MissionConfig& cfg) {
  return cfg.site != Vec2::Zero();
}

bool site_size_ok(const Vec2& site) {
  return site.x() >= 10.0 && site.y() >= 20.0 && site.x() <= 2.0 * limits::kMaxSiteHalf_m &&
         site.y() <= 2.0 * limits::kMaxSiteHalf_m;
}

Vec2 field_half(const MissionConfig& cfg) {
  if (!has_site(cfg)) return Vec2::Constant(0.5 * kPaperArenaSide_m);
  return Vec2(0.5 * cfg.site.x(), 0.5 * cfg.site.y() - kSiteEndBand_m);
}

namespace {

// A count given for the paper's 27 x 27 m arena, for this mission's field: the same density.
std::size_t per_field(const MissionConfig& cfg, std::size_t paper_count) {
  const Vec2 h = field_half(cfg);
  return static_cast<std::size_t>(std::llround(static_cast<double>(paper_count) * 4.0 * h.x() *
                                               h.y() / (kPaperArenaSide_m * kPaperArenaSide_m)));
}

}  // namespace

bool check(const MissionConfig& cfg, std::string& error) {
  const auto fail = [&](const std::string& e) {
    error = e;
    return false;
  };
  if (has_site(cfg)) {
    if (cfg.scenario == "file")
      return fail("--site sizes the generated scenarios (a map file has its own size)");
    if (!site_size_ok(cfg.site))
      return fail("--site must be at least 10 x 20 m and at most " +
                  std::to_string(static_cast<int>(2.0 * limits::kMaxSiteHalf_m)) + " m a side");
    if (cfg.placements.empty() && cfg.site.x() / cfg.ugvs < 2.0)
      return fail("--site is too narrow for " + std::to_string(cfg.ugvs) +
                  " UGVs side by side (2 m each)");
  }
  if (cfg.ugvs < 1 || cfg.ugvs > static_cast<int>(limits::kMaxUgvs)) {
    return fail("--ugvs must be in 1.." + std::to_string(limits::kMaxUgvs));
  }
  if (cfg.uavs < 1 || cfg.uavs > static_cast<int>(limits::kMaxUavs)) {
    return fail("--uavs must be in 1.." + std::to_string(limits::kMaxUavs));
  }
  if (cfg.uavs > 1 && cfg.self_perception)
    return fail("--uavs: the self-perception baseline has no UAV");
  if (!std::isfinite(cfg.faults.uav_lost_at_s))
    return fail("--uav-lost-at must be a number of seconds");
  if (cfg.faults.uav_lost_id >= cfg.uavs)
    return fail("--uav-lost-id " + std::to_string(cfg.faults.uav_lost_id) + ": there are only " +
                std::to_string(cfg.uavs) + " UAVs (0.." + std::to_string(cfg.uavs - 1) + ")");
  const FaultConfig& f = cfg.faults;
  if (f.kill_ugv >= 0 || f.kill_ugv_at_s >= 0.0 || f.restart_after_s >= 0.0) {
    if (f.kill_ugv < 0) return fail("--restart-after: kill a UGV first (--kill-ugv I@T)");
    if (!(f.kill_ugv_at_s > 0.0) || !std::isfinite(f.kill_ugv_at_s))
      return fail("--kill-ugv: UGV I dies at T > 0 s (I@T)");
    if (f.kill_ugv >= cfg.ugvs)
      return fail("--kill-ugv " + std::to_string(f.kill_ugv) + ": there are only " +
                  std::to_string(cfg.ugvs) + " UGVs (0.." + std::to_string(cfg.ugvs - 1) + ")");
    if (!std::isfinite(f.restart_after_s))
      return fail("--restart-after must be a number of seconds");
    if (cfg.self_perception) return fail("--kill-ugv: not in the self-perception baseline");
  }
  if (!cfg.placements.empty() && cfg.placements.size() != static_cast<std::size_t>(cfg.ugvs))
    return fail("a start and a goal for each of the " + std::to_string(cfg.ugvs) + " UGVs");
  for (const UgvPlacement& p : cfg.placements)
    if (p.via.size() > limits::kMaxRouteVias)
      return fail("a route passes at most " + std::to_string(limits::kMaxRouteVias) + " points");
  if (!(cfg.max_time_s > 0.0)) return fail("--max-time must be > 0");
  if (!(cfg.predict_horizon_m > 0.0 && cfg.predict_horizon_m <= 20.0))
    return fail("--predict-horizon must be in (0, 20] m");
  if (cfg.threads < 1 || cfg.threads > 8) return fail("--threads must be in 1..8");
  if (cfg.lidar_columns < 60 || cfg.lidar_columns > static_cast<int>(limits::kMaxLidarColumns)) {
    return fail("--lidar-columns must be in 60.." + std::to_string(limits::kMaxLidarColumns));
  }
  const FaultConfig& fc = cfg.faults;
  if (!(fc.loss >= 0.0 && fc.loss <= 1.0)) return fail("--loss must be in 0..100 %");
  if (!(fc.latency_ms >= 0.0 && fc.latency_ms <= 10000.0 && fc.jitter_ms >= 0.0 &&
        fc.jitter_ms <= 10000.0))
    return fail("--latency-ms and --jitter-ms must be in 0..10000");
  if (!(fc.odom_bias > -0.5 && fc.odom_bias < 0.5))
    return fail("--odom-bias must be in (-50, 50) %");
  const ClockConfig& cc = cfg.clocks;
  if (!(cc.offset_s >= 0.0 && cc.offset_s <= 1e6))
    return fail("--clock-offset-s must be in 0..1e6 s");
  if (!(cc.drift_ppm >= 0.0 && cc.drift_ppm <= 1000.0))
    return fail("--clock-drift-ppm must be in 0..1000");
  if (!(std::isfinite(cc.step_at_s) && std::isfinite(cc.step_s) && std::abs(cc.step_s) <= 1e6))
    return fail("--clock-step must be T:S with |S| <= 1e6 s");
  if (cc.step_at_s >= 0.0 && cc.offset_s + cc.step_s < 0.0)
    return fail("--clock-step: the UAV's clock would read negative (raise --clock-offset-s)");
  return true;
}

bool is_box_field(const std::string& scenario) {
  return scenario == "sparse" || scenario == "dense" || scenario == "pillars";
}

bool build_world(const MissionConfig& cfg, sim::BoxWorld& world, std::string& error,
                 std::vector<std::string>* warnings) {
  const auto generated = [&](Result<sim::BoxWorld> w) {
    if (!w) {
      error = w.status().message();
      return false;
    }
    world = w.value();
    return true;
  };
  if (is_box_field(cfg.scenario)) {
    sim::MapGenConfig gen;
    gen.boxes = per_field(cfg, cfg.boxes > 0 ? cfg.boxes : cfg.scenario == "sparse" ? 40 : 80);
    gen.arena_half = field_half(cfg);
    gen.pillars = cfg.scenario == "pillars";  // 80 pillars, 0.2-0.5 m wide, 0.6-1.2 m tall
    gen.seed = cfg.seed;
    return generated(sim::generate_box_world(gen));
  }
  if (cfg.scenario == "rooms") {
    sim::RoomGenConfig gen = cfg.rooms;
    gen.seed = cfg.seed;
    if (has_site(cfg)) {  // rooms of the same size, furniture as dense
      const Vec2 h = field_half(cfg);
      gen.rooms_x =
          std::max(1, static_cast<int>(std::lround(gen.rooms_x * 2.0 * h.x() / kPaperArenaSide_m)));
      gen.rooms_y =
          std::max(1, static_cast<int>(std::lround(gen.rooms_y * 2.0 * h.y() / kPaperArenaSide_m)));
      gen.furniture = per_field(cfg, gen.furniture);
      gen.arena_half = h;
    }
    return generated(sim::generate_room_world(gen));
  }
  if (cfg.scenario == "file") {
    std::vector<Vec3> points;
    if (!sim::load_pcd(cfg.map_file, points, error)) return false;
    sim::CloudWorldReport report;
    world = sim::box_world_from_points(points, {}, &report);
    std::vector<std::string> found;
    if (!check_map(world, report, cfg, found, error)) {
      error = cfg.map_file + ": " + error;
      return false;
    }
    if (warnings != nullptr) {
      for (const std::string& w : found)
        warnings->push_back(cfg.map_file + ": " + w);
    }
    return true;
  }
  error = "unknown scenario '" + cfg.scenario + "' (sparse, dense, pillars, rooms, or a map file)";
  return false;
}

Pose2 ugv_start(int i) {
  return {Vec2(lane_x(i), start_y(i)), -M_PI / 2};
}
Vec2 ugv_goal(int i) {
  return Vec2(lane_x(i), -start_y(i));
}
Vec3 uav_start() {
  return kUavStart;
}
void lay_out_site(MissionConfig& cfg) {
  // Too narrow a site is left to check(), which says so.
  if (!has_site(cfg) || !cfg.placements.empty() || cfg.site.x() / cfg.ugvs < 2.0) return;
  const double w = cfg.site.x(), y = 0.5 * cfg.site.y() - kSiteStartInset_m;
  for (int i = 0; i < cfg.ugvs; ++i) {
    const double x = -0.5 * w + (i + 0.5) * w / cfg.ugvs;
    cfg.placements.push_back({Pose2{Vec2(x, y), -M_PI / 2}, Vec2(x, -y), {}});
  }
  cfg.uav_start = Vec3(0.0, y - 1.0, 1.0);
}

double default_max_time_s(const MissionConfig& cfg) {
  constexpr double kArena_s = 400.0, kArenaDrive_m = 32.0;
  if (!has_site(cfg)) return kArena_s;
  const double drive_m = cfg.site.y() - 2.0 * kSiteStartInset_m;
  const double per_uav = static_cast<double>(cfg.ugvs) / (4.0 * std::max(cfg.uavs, 1));
  return kArena_s * std::max(1.0, drive_m / kArenaDrive_m) * std::max(1.0, per_uav);
}

Pose2 ugv_start(const MissionConfig& cfg, int i) {
  return cfg.placements.empty() ? ugv_start(i)
                                : cfg.placements.at(static_cast<std::size_t>(i)).start;
}
Vec2 ugv_goal(const MissionConfig& cfg, int i) {
  return cfg.placements.empty() ? ugv_goal(i) : cfg.placements.at(static_cast<std::size_t>(i)).goal;
}

const std::vector<Vec2>& ugv_via(const MissionConfig& cfg, int i) {
  static const std::vector<Vec2> kNone;
  return cfg.placements.empty() ? kNone : cfg.placements.at(static_cast<std::size_t>(i)).via;
}

}  // namespace colag::mission
