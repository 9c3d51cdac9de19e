// colag_sim: one simulated ColAG mission on the host (the real firmware tasks against the
// simulated world, faster than real time), printing the paper's metrics, optionally writing
// them as JSON, drawing the mission as a PNG and recording it as MCAP (ROS 2 topics + truth).
//
// Exit codes: 0 every UGV reached its goal and nothing collided; 1 a collision, or a UGV short
// of its goal (the table and the JSON say where and why); 2 a usage or input error (options, map
// file, an output that cannot be written).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <tuple>

#include "colag/sim/host_program.hpp"
#include "colag/sim/mission/mission.hpp"
#include "colag/sim/mission/world_file.hpp"
#include "colag/sim/mission_png.hpp"
#include "colag/sim/recording/mcap_recorder.hpp"
#include "colag/sim/scenario_options.hpp"
#include "colag/sim/world/pcd_writer.hpp"
#include "colag/ugv/waiting.hpp"

using namespace colag;

namespace {

void print_table(const mission::MissionOutcome& o) {
  // stopped_s: the truth; then the firmware's account of why, in parts (see ugv/waiting.hpp).
  std::printf("\n%-4s %-8s %-9s %8s %9s %7s %7s %7s %7s %7s %7s %8s %8s %6s %8s\n", "ugv",
              "reached", "collided", "reach_s", "stopped_s", "support", "ugv", "path", "start",
              "fault", "manoeuv", "length_m", "clear_m", "nees", "requests");
  for (const auto& u : o.ugvs) {
    char reach[32];
    std::snprintf(reach, sizeof reach, u.reached ? "%.2f" : "-", u.reach_time_s);
    const auto& w = u.waiting_parts;
    std::printf(
        "%-4d %-8s %-9s %8s %9.2f %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f %8.2f %8.2f %6.1f %8llu\n",
        u.id, u.reached ? "yes" : "NO", u.collided ? "YES" : "no", reach, u.stopped_s, w[0], w[1],
        w[2], w[3], w[4], w[5], u.traj_length_m, u.min_clearance_m, u.nees_mean,
        static_cast<unsigned long long>(u.support_requests));
  }
  std::printf("\nsummary (averages per UGV, as in the paper)\n");
  if (o.reach_time_s >= 0.0) {
    std::printf("  UGV reach time      %8.2f s\n", o.reach_time_s);
  } else {
    std::printf("  UGV reach time           - (none reached)\n");
  }
  if (o.reach_missing > 0 && o.reach_time_s >= 0.0)
    std::printf("  (reach time over %d UGVs: %d did not reach)\n",
                static_cast<int>(o.ugvs.size()) - o.reach_missing, o.reach_missing);
  std::printf("  UGV waiting time    %8.2f s (max %.2f s; stood still before its goal)\n",
              o.waiting_time_s, o.max_waiting_time_s);
  std::printf("  waiting for support:");
  for (std::size_t k = 0; k < ugv::kSupportCauses; ++k)
    std::printf("%s %.1f s %s", k == 0 ? "" : ",", o.support_causes_s[k],
                ugv::to_string(static_cast<ugv::SupportCause>(k)));
  std::printf("\n");
  std::printf("  estimator NEES      %8.2f (3 when its covariance is honest)\n", o.nees_mean);
  std::printf("  UGV traj. length    %8.2f m\n", o.ugv_traj_length_m);
  std::printf("  UAV traj. length    %8.2f m\n", o.uav_traj_length_m);
  if (o.config.uavs > 1)
    std::printf("  UAVs closest        %8.2f m (3-D, airborne)\n", o.uav_min_separation_m);
  std::printf("  network in per UGV  %8.1f kB/s (CDR; the UAV sends %.1f kB/s in all)\n",
              o.bytes_in_per_ugv_per_s / 1e3, o.uav_bytes_out_per_s / 1e3);
  for (std::size_t k = 0; k < msg::kTopicCount; ++k) {
    const double b = o.bytes_in_per_ugv_by_topic_per_s[k];
    if (b >= 50.0) std::printf("    %-28s %6.1f kB/s\n", msg::kTopicTable[k].name, b / 1e3);
  }
  std::printf("  collisions          %8d\n", o.collisions);
  std::printf("  all reached         %8s\n", o.all_reached ? "yes" : "NO");
  for (const auto& u : o.ugvs) {
    if (!u.reached || u.collided) std::printf("  UGV %-2d              %s\n", u.id, u.end.c_str());
  }
  if (o.map_patches > 0) {
    std::printf("  map patches         %8llu (%.1f B payload each)\n",
                static_cast<unsigned long long>(o.map_patches),
                static_cast<double>(o.map_patch_bytes) / static_cast<double>(o.map_patches));
    std::printf("  team filter         %8llu UGVs located anew, %llu returns kept out of the map\n",
                static_cast<unsigned long long>(o.team_located),
                static_cast<unsigned long long>(o.team_returns_dropped));
  }
  if (o.base_fault.injected) {
    const mission::BaseFaultOutcome& f = o.base_fault;
    std::printf(
        "  base fault (UGV 0)  firmware in fault after %.2f s, wheels still after %.2f s, "
        "%s\n",
        f.firmware_fault_after_s, f.still_after_s,
        f.max_speed_after_still < 0.01 ? "never moved again" : "MOVED AGAIN");
  }
  std::printf("  simulated %.1f s in %.2f s wall (%.0fx real time)\n", o.sim_time_s, o.wall_time_s,
              o.sim_time_s / std::max(o.wall_time_s, 1e-9));
}

int run(int argc, char** argv) {
  CLI::App app{"colag_sim: one simulated ColAG mission (UAV + blind UGVs) on the host"};
  mission::MissionConfig cfg;
  std::string map_file, ablation = "none", json_path, png_path, mcap_path;
  bool quiet = false, verbose = false;
  auto* scenario = app.add_option("--scenario", cfg.scenario,
                                  "generated map: sparse (40 boxes), dense (80), pillars (80, "
                                  "0.2-0.5 m wide, 0.6-1.2 m tall) or rooms (3 x 3 rooms, walls "
                                  "with doorways, 16 boxes of furniture)")
                       ->check(CLI::IsMember(mission::kGeneratedScenarios));
  auto* map_opt = app.add_option("--map", map_file, "a PCD map instead (ascii or binary; x y z)")
                      ->excludes(scenario)
                      ->check(CLI::ExistingFile);
  auto* ugvs_opt = app.add_option("--ugvs", cfg.ugvs, "number of UGVs")
                       ->check(CLI::Range(1, static_cast<int>(limits::kMaxUgvs)));
  auto* site_opt = sim::add_site_option(app, cfg.site)->excludes(map_opt);
  std::string scenario_file;
  app.add_option("--scenario-file", scenario_file,
                 "a YAML scenario: the map, each UGV's start and goal, the UAV's start, the world, "
                 "faults (config/scenarios/README.md); options given as well override its values")
      ->excludes(scenario)
      ->excludes(map_opt)
      ->excludes(ugvs_opt)
      ->excludes(site_opt);
  std::string world_name = "ideal";
  app.add_option("--world", world_name,
                 "ideal (the noise the firmware's models assume: the paper's tables), field (what "
                 "real wheels, cameras, LiDARs and clocks do), or a YAML scenario file "
                 "(config/worlds/field.yaml documents every key)");
  app.add_option("--seed", cfg.seed, "seed of the map, the noise and the network")
      ->check(sim::kSeed);
  app.add_option("--ablation", ablation,
                 "none, no-rpe, no-uncertainty, no-scheduling, no-time-windows")
      ->check(
          CLI::IsMember({"none", "no-rpe", "no-uncertainty", "no-scheduling", "no-time-windows"}));
  app.add_flag("--self-perception", cfg.self_perception,
               "baseline: every UGV has its own LiDAR and true pose, no UAV");
  auto* max_time_opt =
      app.add_option("--max-time", cfg.max_time_s,
                     "simulated seconds before giving up (default 400; on a --site, 400 per 32 m "
                     "of its length, times the UGVs per UAV beyond 4)")
          ->check(sim::positive_up_to(1e6));
  app.add_option("--lidar-columns", cfg.lidar_columns, "LiDAR columns per turn (1200 = 0.3 deg)")
      ->check(CLI::Range(60, 1200));
  app.add_option("--predict-horizon", cfg.predict_horizon_m,
                 "UGV collision-prediction horizon, m (paper: 2)")
      ->check(CLI::Range(0.1, 20.0));
  app.add_option("--scouting", cfg.scouting,
                 "on: with nothing requested, the UAV maps where the UGVs' paths meet unknown "
                 "ground soonest (beyond the paper)")
      ->transform(
          CLI::CheckedTransformer(std::map<std::string, bool>{{"on", true}, {"off", false}}))
      ->default_str("off");
  app.add_option("--uavs", cfg.uavs,
                 "UAVs sharing the support (beyond the paper): each serves the UGVs it is best "
                 "placed for; one that is lost has its UGVs taken over")
      ->check(CLI::Range(1, static_cast<int>(limits::kMaxUavs)));
  app.add_option("--threads", cfg.threads,
                 "cores the simulation may use (the results are the same for any number)")
      ->check(CLI::Range(1, 8));
  // Fault injection.
  double loss_pct = 0.0, odom_bias_pct = 0.0;
  std::string blackout, uav_blackout, rpe_blackout;
  auto* faults = app.add_option_group("faults", "fault injection");
  faults->add_option("--loss", loss_pct, "share of messages lost, % (every topic)")
      ->check(CLI::Range(0.0, 100.0));
  faults->add_option("--latency-ms", cfg.faults.latency_ms, "network latency, ms")
      ->check(CLI::Range(0.0, 10000.0));
  faults->add_option("--jitter-ms", cfg.faults.jitter_ms, "+ uniform jitter, ms (reorders)")
      ->check(CLI::Range(0.0, 10000.0));
  faults->add_option("--blackout", blackout,
                     "T0:T1 s: every robot is silent (every topic of every robot lost)");
  faults->add_option("--uav-blackout", uav_blackout, "T0:T1 s: the UAV is silent (all its topics)");
  faults->add_option("--rpe-blackout", rpe_blackout, "T0:T1 s: no relative poses");
  faults->add_option("--odom-bias", odom_bias_pct, "wheel-encoder scale error, %")
      ->check(CLI::Range(-49.0, 49.0));
  faults
      ->add_option("--base-fault-at", cfg.faults.base_fault_at_s,
                   "UGV 0's base faults at this time, s (--ugv-base: an ODrive motor error, an "
                   "AgileX e-stop, our controller silent); UGV 0 must stop and stay stopped")
      ->check(sim::positive_up_to(1e6));
  faults
      ->add_option("--uav-lost-at", cfg.faults.uav_lost_at_s,
                   "a UAV's board (the last's, or --uav-lost-id's) dies at this time, s: it "
                   "stops and falls silent (with --uavs 2+ the others take its UGVs over)")
      ->check(sim::positive_up_to(1e6));
  faults
      ->add_option("--uav-lost-id", cfg.faults.uav_lost_id,
                   "which UAV --uav-lost-at loses (default: the last; 0 is the time server)")
      ->check(CLI::Range(0, static_cast<int>(limits::kMaxUavs) - 1));
  std::string kill_ugv;
  faults->add_option("--kill-ugv", kill_ugv,
                     "I@T: UGV I's firmware process dies at T s (its state and readers with it; "
                     "its base stops it), as scripts/sitl.sh --kill-ugv does with ugv_fw");
  faults
      ->add_option("--restart-after", cfg.faults.restart_after_s,
                   "with --kill-ugv: a new process starts S s later, from the same "
                   "configuration (it must localise again and finish its mission)")
      ->check(CLI::Range(0.0, 1e6));
  // Clocks: every robot keeps its own (fleet time is the UAV's; the UGVs learn it over DDS).
  std::string clock_step;
  auto* clocks = app.add_option_group("clocks", "each robot's own clock");
  clocks
      ->add_option(
          "--clock-offset-s", cfg.clocks.offset_s,
          "each UGV's (and UAV 1+'s) clock reads up to this many seconds more or less than UAV 0's")
      ->check(CLI::Range(0.0, 1e6));
  clocks
      ->add_option("--clock-drift-ppm", cfg.clocks.drift_ppm,
                   "each robot's clock runs up to this fast or slow (crystals: 10-50 ppm)")
      ->check(CLI::Range(0.0, 1000.0));
  clocks->add_option("--clock-step", clock_step,
                     "T:S: at mission time T s the UAV's clock jumps by S s (S may be negative)");
  // The camera, over the world's (to reproduce a given robot's without writing a world file).
  double fov_deg = 0.0, rpe_range = 0.0, rpe_sigma = 0.0, rpe_true_scale = 0.0;
  auto* camera = app.add_option_group("camera", "the UAV's relative-pose camera (over --world's)");
  auto* fov_opt = camera
                      ->add_option("--camera-fov-deg", fov_deg,
                                   "half-angle of its view cone from straight down, deg")
                      ->check(CLI::Range(1.0, 180.0));
  auto* range_opt = camera->add_option("--rpe-range-m", rpe_range, "how far it detects tags, m")
                        ->check(sim::positive_up_to(100.0));
  auto* sigma_opt = camera->add_option("--rpe-sigma-m", rpe_sigma, "position sigma it reports, m")
                        ->check(sim::positive_up_to(10.0));
  auto* true_opt = camera
                       ->add_option("--rpe-true-scale", rpe_true_scale,
                                    "its true error sigma is this x what it reports")
                       ->check(sim::positive_up_to(100.0));
  sim::add_ugv_base_option(app, cfg.ugv_base);
  app.add_option("--json", json_path, "write the metrics as JSON to this file");
  app.add_option("--png", png_path, "draw the mission into this PNG file");
  app.add_option("--mcap", mcap_path,
                 "record the mission into this MCAP file (ROS 2 topics of every robot and the "
                 "world's truth; open it in Foxglove or Lichtblick)");
  std::string save_map;
  app.add_option("--save-map", save_map,
                 "write the scenario's map as a PCD file (the paper's format) and exit");
  app.add_flag("--quiet", quiet, "no progress bar, no table");
  app.add_flag("--verbose", verbose,
               "also list every stop of every UGV and the host time of each task");
  app.footer(
      "Exit codes: 0 every UGV reached its goal and nothing collided; 1 a collision or a UGV\n"
      "short of its goal; 2 a usage or input error.");
  if (const auto code = sim::parse_command_line(app, argc, argv)) return *code;
  if (!map_file.empty()) {
    cfg.scenario = "file";
    cfg.map_file = map_file;
  }
  mission::parse_ablation(ablation, cfg.ablation);
  if (const int code =
          sim::apply_scenario_options(app, "colag_sim", scenario_file, world_name, cfg))
    return code;
  if (!scenario_file.empty()) {  // these two are kept as percentages until below
    if (app.get_option("--loss")->count() == 0) loss_pct = cfg.faults.loss * 100.0;
    if (app.get_option("--odom-bias")->count() == 0) odom_bias_pct = cfg.faults.odom_bias * 100.0;
  }
  if (fov_opt->count() + range_opt->count() + sigma_opt->count() + true_opt->count() > 0)
    cfg.world.name += "+camera";  // the JSON and the table say the world is not the file's
  if (fov_opt->count() > 0) cfg.world.camera.fov_half_angle_deg = fov_deg;
  if (range_opt->count() > 0) cfg.world.camera.range_m = rpe_range;
  if (sigma_opt->count() > 0) cfg.world.camera.sigma_position_m = rpe_sigma;
  if (true_opt->count() > 0) cfg.world.camera.true_sigma_scale = rpe_true_scale;
  cfg.faults.loss = loss_pct / 100.0;
  cfg.faults.odom_bias = odom_bias_pct / 100.0;
  for (const auto& [text, window, name] :
       {std::tuple{blackout, &cfg.faults.blackout, "--blackout"},
        std::tuple{uav_blackout, &cfg.faults.uav_blackout, "--uav-blackout"},
        std::tuple{rpe_blackout, &cfg.faults.rpe_blackout, "--rpe-blackout"}}) {
    if (!text.empty() && !mission::parse_window(text, *window)) {
      std::fprintf(stderr, "colag_sim: %s: expected T0:T1 in seconds with 0 <= T0 < T1, got '%s'\n",
                   name, text.c_str());
      return 2;
    }
  }

  if (!kill_ugv.empty() &&
      !mission::parse_kill(kill_ugv, cfg.faults.kill_ugv, cfg.faults.kill_ugv_at_s)) {
    std::fprintf(stderr, "colag_sim: --kill-ugv: expected I@T (UGV I, T > 0 s), got '%s'\n",
                 kill_ugv.c_str());
    return 2;
  }
  if (!clock_step.empty()) {
    const auto colon = clock_step.find(':');
    char* end = nullptr;
    const double at = std::strtod(clock_step.c_str(), &end);
    const bool at_ok = colon != std::string::npos && colon > 0 && end == clock_step.c_str() + colon;
    const double by = at_ok ? std::strtod(clock_step.c_str() + colon + 1, &end) : 0.0;
    if (!at_ok || *end != '\0' || !(at >= 0.0) || !std::isfinite(by) ||
        colon + 1 == clock_step.size()) {
      std::fprintf(stderr,
                   "colag_sim: --clock-step: expected T:S in seconds with T >= 0, got '%s'\n",
                   clock_step.c_str());
      return 2;
    }
    cfg.clocks.step_at_s = at;
    cfg.clocks.step_s = by;
  }

  mission::lay_out_site(cfg);
  if (scenario_file.empty() && max_time_opt->count() == 0)
    cfg.max_time_s = mission::default_max_time_s(cfg);
  if (!save_map.empty()) {
    sim::BoxWorld world;
    std::string error;
    if (!mission::build_world(cfg, world, error) || !sim::save_pcd(save_map, world, error)) {
      std::fprintf(stderr, "colag_sim: %s\n", error.c_str());
      return 2;
    }
    if (!quiet)
      std::printf("colag_sim: %zu boxes written to %s\n", world.boxes.size(), save_map.c_str());
    return 0;
  }

  // Outputs that cannot be written fail now, not after the mission.
  if (!json_path.empty() && !std::ofstream(json_path)) {
    std::fprintf(stderr, "colag_sim: --json %s: cannot write there\n", json_path.c_str());
    return 2;
  }
  if (!png_path.empty()) {
    const bool png =
        png_path.size() > 4 && (png_path.ends_with(".png") || png_path.ends_with(".PNG"));
    if (!png || !std::ofstream(png_path)) {
      std::fprintf(stderr, "colag_sim: --png %s: %s\n", png_path.c_str(),
                   png ? "cannot write there" : "the file name must end in .png");
      return 2;
    }
  }

  std::string error;
  mission::McapRecorder recorder;
  if (!mcap_path.empty() && !recorder.open(mcap_path, error)) {
    std::fprintf(stderr, "colag_sim: --mcap: %s\n", error.c_str());
    return 2;
  }

  const bool bar = !quiet && isatty(STDERR_FILENO);
  if (bar) {
    cfg.progress = [](double f) {
      const int width = 40, done = static_cast<int>(std::min(f, 1.0) * width);
      std::fprintf(stderr, "\r[%.*s%*s] %3.0f%% of max time", done,
                   "========================================", width - done, "",
                   100.0 * std::min(f, 1.0));
    };
  }
  cfg.warn = [](const std::string& w) {
    std::fprintf(stderr, "colag_sim: warning: %s\n", w.c_str());
  };
  mission::MissionTrace trace;
  const auto outcome = mission::run_mission(cfg, png_path.empty() && !verbose ? nullptr : &trace,
                                            &error, mcap_path.empty() ? nullptr : &recorder);
  if (bar) std::fprintf(stderr, "\r%*s\r", 60, "");
  if (!outcome) {
    std::fprintf(stderr, "colag_sim: %s\n", error.c_str());
    return 2;
  }
  const mission::MissionOutcome& o = outcome.value();
  if (!quiet) {
    std::printf("colag_sim: %s map, %s world, %d UGV%s, seed %llu, ablation %s%s\n",
                cfg.scenario == "file" ? cfg.map_file.c_str() : cfg.scenario.c_str(),
                cfg.world.name.c_str(), cfg.ugvs, cfg.ugvs == 1 ? "" : "s",
                static_cast<unsigned long long>(cfg.seed), mission::to_string(cfg.ablation),
                cfg.self_perception ? ", self-perception baseline" : "");
    print_table(o);
  }
  if (verbose) {
    std::printf("\nstops (UGV, from - to, where, why)\n");
    for (const auto& s : trace.stops) {
      std::printf("  %2d  %7.1f - %7.1f s  (%6.2f, %6.2f)  %s\n", s.ugv, s.from_s, s.to_s,
                  s.where.x(), s.where.y(), mission::standing_reason(s.why, s.blocked).c_str());
    }
    double total = 0.0;
    for (const auto& t : o.task_times)
      total += t.total_s;
    std::printf("\nhost CPU per task (all robots; %d thread%s)\n", cfg.threads,
                cfg.threads == 1 ? "" : "s");
    std::printf("  %-16s %9s %9s %6s %12s\n", "task", "steps", "total s", "share", "longest ms");
    for (const auto& t : o.task_times) {
      std::printf("  %-16s %9llu %9.3f %5.1f%% %12.3f\n", t.name.c_str(),
                  static_cast<unsigned long long>(t.steps), t.total_s,
                  total > 0 ? 100.0 * t.total_s / total : 0.0, t.longest_ms);
    }
  }
  if (!json_path.empty()) {
    std::ofstream json(json_path);
    json << mission::to_json(o) << "\n";
    if (!json.flush()) {
      std::fprintf(stderr, "colag_sim: --json %s: cannot write there\n", json_path.c_str());
      return 2;
    }
    if (!quiet) std::printf("  metrics: %s\n", json_path.c_str());
  }
  if (!mcap_path.empty()) {
    if (!recorder.close(error)) {
      std::fprintf(stderr, "colag_sim: --mcap: %s\n", error.c_str());
      return 2;
    }
    if (!quiet) {
      std::printf("  recording: %s (%llu messages, %.1f MB)\n", mcap_path.c_str(),
                  static_cast<unsigned long long>(recorder.messages()),
                  static_cast<double>(recorder.bytes()) / 1e6);
    }
  }
  if (!png_path.empty()) {
    if (!programs::draw_mission(trace, o, png_path, error)) {
      std::fprintf(stderr, "colag_sim: %s\n", error.c_str());
      return 2;
    }
    if (!quiet) std::printf("  picture: %s\n", png_path.c_str());
  }
  if (o.time_limit_reached) {
    const auto short_of = std::count_if(o.ugvs.begin(), o.ugvs.end(),
                                        [](const auto& u) { return !u.reached && !u.collided; });
    std::fprintf(stderr,
                 "colag_sim: the time limit (%.0f s) ended the mission with %d of %d UGVs still "
                 "short of their goals: --max-time gives it longer\n",
                 cfg.max_time_s, static_cast<int>(short_of), static_cast<int>(o.ugvs.size()));
  }
  return mission::exit_code(o);
}

}  // namespace

int main(int argc, char** argv) {
  return colag::sim::guarded_main("colag_sim", 2, [&] { return run(argc, argv); });
}
