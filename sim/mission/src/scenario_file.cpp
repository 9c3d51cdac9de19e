#include "colag/sim/mission/scenario_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "colag/board/yaml_reader.hpp"
#include "colag/common/limits.hpp"
#include "colag/sim/mission/world_file.hpp"

namespace colag::mission {

namespace {
constexpr double kMinStartSeparation_m = 1.0;  // two bodies (0.3 m radius) and a margin

// The firmware's maps are windows that move over the site (map_window.hpp): any place within
// limits::kMaxSiteHalf_m of the world frame's origin.
bool inside_maps(const Vec2& p) {
  return p.cwiseAbs().maxCoeff() <= limits::kMaxSiteHalf_m;
}

std::string outside_text(const Vec2& p) {
  char text[160];
  std::snprintf(text, sizeof text,
                "(%.1f, %.1f) is beyond the largest site (%.0f m from the origin)", p.x(), p.y(),
                limits::kMaxSiteHalf_m);
  return text;
}

// A generator's parameters: `boxes` for the box and pillar fields; `rooms: [x, y]`, `door_m`
// and `furniture` for rooms. Each only with its generator.
void read_generator_parameters(board::Reader& r, const YAML::Node& map, MissionConfig& c) {
  const bool rooms = c.scenario == "rooms";
  const bool field = is_box_field(c.scenario);
  if (r.ok() && map["site"] && !(field || rooms))
    r.fail("map.site", "sizes a generated map (a PCD has its own size)");
  if (double site[2] = {}; r.ok() && r.vector(map, "map", "site", site, 2)) {
    if (!site_size_ok(Vec2(site[0], site[1])))
      r.fail("map.site", "expected [width_m, length_m], at least [10, 20]");
    else
      c.site = Vec2(site[0], site[1]);
  }
  for (const char* key : {"boxes", "rooms", "door_m", "furniture"}) {
    if (!r.ok() || !map[key]) continue;
    if ((std::string(key) == "boxes" && !field) || (std::string(key) != "boxes" && !rooms))
      r.fail(std::string("map.") + key, std::string("not a parameter of this map (") +
                                            (field   ? "boxes"
                                             : rooms ? "rooms, door_m, furniture"
                                                     : "none for a PCD") +
                                            ")");
  }
  int boxes = 0;
  r.get(map, "map", "boxes", boxes, 1, 400);
  c.boxes = static_cast<std::size_t>(boxes);
  if (double grid[2] = {}; r.ok() && r.vector(map, "map", "rooms", grid, 2)) {
    const auto whole = [](double v) { return v >= 1 && v <= 8 && v == std::floor(v); };
    if (!whole(grid[0]) || !whole(grid[1])) {
      r.fail("map.rooms", "expected [x, y]: rooms along x and y, each 1..8");
    } else {
      c.rooms.rooms_x = static_cast<int>(grid[0]);
      c.rooms.rooms_y = static_cast<int>(grid[1]);
    }
  }
  r.get(map, "map", "door_m", c.rooms.door_m, 1.0, 5.0);
  int furniture = static_cast<int>(c.rooms.furniture);
  r.get(map, "map", "furniture", furniture, 0, 200);
  c.rooms.furniture = static_cast<std::size_t>(furniture);
}

}  // namespace

bool load_scenario_file(const std::string& file, MissionConfig& cfg, std::string& error) {
  YAML::Node root;
  if (!board::load_yaml_file(file, root, error)) return false;
  board::Reader r(file, error);
  if (!root.IsMap()) {
    r.fail("(top level)", "expected a mapping (see config/scenarios/README.md)");
    return false;
  }
  r.only(root, "", {"map", "seed", "world", "max_time_s", "uav", "ugvs", "faults"});
  MissionConfig c = cfg;
  c.scenario_file = file;

  const YAML::Node map = board::child(root, "map");
  r.require(root, "", "map");
  r.only(map, "map",
         {"generator", "pcd", "units", "site", "boxes", "rooms", "door_m", "furniture"});
  std::string generator, pcd, units = "m";
  r.get(map, "map", "generator", generator);
  r.get(map, "map", "pcd", pcd);
  r.get(map, "map", "units", units);
  if (r.ok() && generator.empty() == pcd.empty())
    r.fail("map", "give either generator (sparse, dense, pillars, rooms) or pcd (a file)");
  if (r.ok() && !generator.empty()) {
    if (std::find(kGeneratedScenarios.begin(), kGeneratedScenarios.end(), generator) ==
        kGeneratedScenarios.end())
      r.fail("map.generator", "expected sparse, dense, pillars or rooms");
    c.scenario = generator;
  }
  if (r.ok() && !pcd.empty()) {
    c.scenario = "file";
    c.map_file = board::relative_to(file, pcd);
  }
  read_generator_parameters(r, map, c);
  if (r.ok() && units != "m")
    r.fail("map.units", "only m (metres) is supported: convert the map (x, y, z in metres)");

  r.get(root, "", "seed", c.seed, std::uint64_t{0}, ~std::uint64_t{0});
  r.get(root, "", "max_time_s", c.max_time_s, 1.0, 1e6);
  std::string world;
  r.get(root, "", "world", world);
  if (r.ok() && !world.empty()) {
    const std::string name =
        world == "ideal" || world == "field" ? world : board::relative_to(file, world);
    std::string world_error;
    if (!world_from_name(name, c.world, world_error)) r.fail("world", world_error);
  }

  const YAML::Node uav = board::child(root, "uav");
  r.only(uav, "uav", {"start", "count"});
  r.get(uav, "uav", "count", c.uavs, 1, static_cast<int>(limits::kMaxUavs));
  double u[3] = {c.uav_start.x(), c.uav_start.y(), c.uav_start.z()};
  const bool uav_given = r.vector(uav, "uav", "start", u, 3);
  if (uav_given) {
    if (!inside_maps(Vec2(u[0], u[1]))) r.fail("uav.start", outside_text(Vec2(u[0], u[1])));
    if (!(u[2] >= 0.5 && u[2] <= 10.0)) r.fail("uav.start", "its height must be in 0.5..10 m");
    c.uav_start = Vec3(u[0], u[1], u[2]);
  }

  const YAML::Node ugvs = board::child(root, "ugvs");
  r.require(root, "", "ugvs");
  c.placements.clear();
  if (r.ok() && ugvs.IsScalar()) {
    // A count: the generated site's layout (side by side along its north edge).
    int count = 0;
    r.get(root, "", "ugvs", count, 1, static_cast<int>(limits::kMaxUgvs));
    if (r.ok() && !has_site(c))
      r.fail("ugvs", "a number of UGVs needs map.site (else list each {start, goal})");
    c.ugvs = count;
    if (std::string why; r.ok() && !check(c, why)) r.fail("ugvs", why);
    lay_out_site(c);
    if (uav_given) c.uav_start = Vec3(u[0], u[1], u[2]);
  } else if (r.ok() && (!ugvs.IsSequence() || ugvs.size() < 1 || ugvs.size() > limits::kMaxUgvs)) {
    r.fail("ugvs", "expected a list of 1.." + std::to_string(limits::kMaxUgvs) +
                       " UGVs, each {start: [x, y, yaw_deg], goal: [x, y]}");
  }
  for (std::size_t i = 0; r.ok() && ugvs.IsSequence() && i < ugvs.size(); ++i) {
    const std::string path = "ugvs[" + std::to_string(i) + "]";
    const YAML::Node ugv = ugvs[i];
    r.only(ugv, path, {"start", "goal", "via"});
    r.require(ugv, path, "start");
    r.require(ugv, path, "goal");
    double s[3] = {}, g[2] = {};
    if (!r.vector(ugv, path, "start", s, 3) || !r.vector(ugv, path, "goal", g, 2)) break;
    UgvPlacement p{{Vec2(s[0], s[1]), s[2] * M_PI / 180.0}, Vec2(g[0], g[1]), {}};
    r.points(ugv, path, "via", limits::kMaxRouteVias,
             [&](double x, double y) { p.via.emplace_back(x, y); });
    if (!inside_maps(p.start.p)) r.fail(path + ".start", outside_text(p.start.p));
    if (!inside_maps(p.goal)) r.fail(path + ".goal", outside_text(p.goal));
    for (std::size_t k = 0; k < p.via.size(); ++k)
      if (!inside_maps(p.via[k]))
        r.fail(path + ".via[" + std::to_string(k) + "]", outside_text(p.via[k]));
    for (std::size_t k = 0; r.ok() && k < c.placements.size(); ++k) {
      const double d = (c.placements[k].start.p - p.start.p).norm();
      if (d < kMinStartSeparation_m) {
        char text[160];
        std::snprintf(text, sizeof text, "%.2f m from ugvs[%zu].start: UGVs start %.0f m apart", d,
                      k, kMinStartSeparation_m);
        r.fail(path + ".start", text);
      }
    }
    c.placements.push_back(p);
  }
  if (ugvs.IsSequence()) c.ugvs = static_cast<int>(c.placements.size());

  const YAML::Node faults = board::child(root, "faults");
  r.only(faults, "faults",
         {"loss_percent", "latency_ms", "jitter_ms", "blackout", "uav_blackout", "rpe_blackout",
          "odom_bias_percent", "uav_lost_at_s", "uav_lost_id", "kill_ugv", "kill_ugv_at_s",
          "restart_after_s"});
  r.get(faults, "faults", "kill_ugv", c.faults.kill_ugv, 0, static_cast<int>(limits::kMaxUgvs) - 1);
  r.get(faults, "faults", "kill_ugv_at_s", c.faults.kill_ugv_at_s, 0.0, 1e6);
  r.get(faults, "faults", "restart_after_s", c.faults.restart_after_s, 0.0, 1e6);
  r.get(faults, "faults", "uav_lost_at_s", c.faults.uav_lost_at_s, 0.0, 1e6);
  r.get(faults, "faults", "uav_lost_id", c.faults.uav_lost_id, 0,
        static_cast<int>(limits::kMaxUavs) - 1);
  double loss = c.faults.loss * 100.0;
  r.get(faults, "faults", "loss_percent", loss, 0.0, 100.0);
  c.faults.loss = loss / 100.0;
  r.get(faults, "faults", "latency_ms", c.faults.latency_ms, 0.0, 10000.0);
  r.get(faults, "faults", "jitter_ms", c.faults.jitter_ms, 0.0, 10000.0);
  // Outages: [from, to] in mission seconds (colag_sim's --blackout T0:T1 and the like).
  for (const auto& [key, window] : {std::pair{"blackout", &c.faults.blackout},
                                    std::pair{"uav_blackout", &c.faults.uav_blackout},
                                    std::pair{"rpe_blackout", &c.faults.rpe_blackout}}) {
    if (double w[2] = {}; r.ok() && r.vector(faults, "faults", key, w, 2)) {
      if (!(w[0] >= 0.0 && w[1] > w[0]))
        r.fail(std::string("faults.") + key, "expected [from_s, to_s] with 0 <= from_s < to_s");
      else
        *window = {w[0], w[1]};
    }
  }
  double bias = c.faults.odom_bias * 100.0;
  r.get(faults, "faults", "odom_bias_percent", bias, -49.0, 49.0);
  c.faults.odom_bias = bias / 100.0;
  if (!r.ok()) return false;
  cfg = c;
  return true;
}

}  // namespace colag::mission
