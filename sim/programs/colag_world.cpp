// colag_world: the simulated world as its own process, for software in the loop (SITL). The
// robots' firmware runs unchanged as separate processes — uav_fw (robot.hal: sim) and one ugv_fw
// per UGV (can.interface: sim) — and reaches the world only over DDS: the sim link on domain
// D + 1 (CAN frames, the UAV's state, setpoints, LiDAR scans, camera frames) while the robots
// talk to each other on domain D. The world listens to the robots' own topics on D for the
// metrics, runs in real time, and writes the same metrics JSON as colag_sim.
//
//   colag_world --scenario sparse --ugvs 3 --seed 1 [--world ideal|field|FILE] [--domain D]
//               [--max-time S] [--json F]
//               [--time-scale X]   (X simulated seconds per second; the robots get the same)
//   colag_world --world field --print-uav-sensors   (the uav.yaml sections that describe the
//               simulated UAV's LiDAR and camera to uav_fw, as a board's config would)
//
// The mission clock starts when every robot has been heard (their status, the UAV's odometry).
// Exit codes: 0 the mission ran (see the JSON for how it went), 1 DDS failed, 2 usage,
// 3 a robot never appeared or went silent.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "colag/platform/dds/dds_transport.hpp"
#include "colag/platform/realtime_executor.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/bridge/px4_stack_bridge.hpp"
#include "colag/sim/bridge/world_bridge.hpp"
#include "colag/sim/host_program.hpp"
#include "colag/sim/mission/mission.hpp"
#include "colag/sim/mission/truth_metrics.hpp"
#include "colag/sim/mission/world_file.hpp"
#include "colag/sim/mission/world_setup.hpp"
#include "colag/sim/scenario_options.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "colag/ugv/waiting.hpp"

using namespace colag;
using namespace std::chrono_literals;

namespace {

// Where each UGV truly was over the last second, in the UAV odometry's frame (where its
// estimate is): a UGV's status is held against the truth at its own stamp (every process
// reads the host's clock), not at the moment it arrives.
class TruthHistory {
 public:
  explicit TruthHistory(int ugvs) : rings_(static_cast<std::size_t>(ugvs)) {}
  void record(const sim::SimWorld& world, TimePoint now) {
    for (std::size_t i = 0; i < rings_.size(); ++i) {
      rings_[i][next_] = {
          now, world.odometry_frame().to_odometry(world.ugv(static_cast<int>(i)).pose())};
    }
    next_ = (next_ + 1) % kSteps;
  }
  // The pose within 30 ms of `t`, if one was recorded.
  std::optional<Pose2> at(std::size_t ugv, TimePoint t) const {
    if (ugv >= rings_.size()) return std::nullopt;
    for (const auto& [when, pose] : rings_[ugv])
      if (when != TimePoint{} && std::abs(to_seconds(when - t)) <= 0.03) return pose;
    return std::nullopt;
  }

 private:
  static constexpr std::size_t kSteps = 50;  // a second of 20 ms steps
  std::vector<std::array<std::pair<TimePoint, Pose2>, kSteps>> rings_;
  std::size_t next_ = 0;
};

class WorldStep final : public platform::Task {
 public:
  WorldStep(sim::SimWorld& world, TruthHistory& truth) : world_(world), truth_(truth) {}
  const char* name() const override { return "world"; }
  void step(TimePoint now) override {
    // Real time: the step covers the time since the last one (more when activations were skipped).
    const double dt = last_ == TimePoint{} ? 0.02 : std::clamp(to_seconds(now - last_), 0.0, 0.1);
    last_ = now;
    world_.step(now, dt);
    truth_.record(world_, now);
  }

 private:
  sim::SimWorld& world_;
  TruthHistory& truth_;
  TimePoint last_{};
};

// The simulated UAV's sensors as uav_fw's config describes a board's (see config/uav.example.yaml
// and, for its flight stack on PX4's and ROS 2's wire formats, config/uav_px4.example.yaml).
void print_uav_sensors(const sim::SimWorldConfig& wc, const sim::Px4StackConfig* px4) {
  const uav::LidarBeamPattern p = mission::beam_pattern_of(wc.lidar);
  const uav::CameraView v = mission::camera_view_of(wc.camera);
  std::printf(
      "lidar: {beams: %d, lowest_elevation_deg: %.3f, elevation_step_deg: %.3f, columns: %d",
      p.beams, p.lowest_elevation_deg, p.elevation_step_deg, p.columns);
  if (px4 != nullptr) {
    // Each scan is published as it is taken: no latency beyond the link's.
    std::printf(", topic: %s, dds_domain: %u, max_range_m: %.1f, latency_ms: 0",
                px4->lidar_topic.c_str(), px4->dds_domain, wc.lidar.max_range_m);
  }
  std::printf("}\n");
  // The simulated camera tells the UGVs apart without tags; they stand at the default height.
  std::printf("camera: {%smax_range_m: %.3f, fov_half_angle_deg: %.3f}\n",
              px4 != nullptr ? "device: sim, " : "", v.range_m, std::min(v.half_angle_deg, 180.0));
  if (px4 == nullptr) return;
  std::printf("px4: {release: \"%s\", dds_domain: %u}\n", hal::px4::to_string(px4->release),
              px4->dds_domain);
  std::printf("odometry: {source: fast_lio, topic: %s, dds_domain: %u, latency_ms: %.1f}\n",
              px4->odometry_topic.c_str(), px4->dds_domain,
              to_seconds(wc.uav.odometry.latency) * 1e3);
}

// colag_world's flight stack (--uav-stack px4), and the faults it can play.
// The PX4 fault to play, if any (one per run).
enum class Px4Fault : std::uint8_t { kNone, kSilent, kFailsafe, kPilot };

// colag_world's flight stack (--uav-stack px4) and the fault it plays. After the fault it measures
// how long the UGVs take to stand still (the firmware's promise: within a second, since the UAV
// no longer supports them and may come down anywhere).
class Px4StackStep final : public platform::Task {
 public:
  Px4StackStep(sim::Px4StackBridge& bridge, const sim::SimWorld& world, Px4Fault fault,
               double fault_at_s)
      : bridge_(bridge), world_(world), fault_(fault), fault_at_s_(fault_at_s) {}
  const char* name() const override { return "px4_stack"; }
  Status init(TimePoint now) override {
    start_ = now;
    return Status::ok();
  }
  void step(TimePoint now) override {
    const double t = to_seconds(now - start_);
    if (fault_ != Px4Fault::kNone && !injected_ && t >= fault_at_s_) {
      injected_ = true;
      switch (fault_) {
        case Px4Fault::kSilent:
          bridge_.set_silent(true);
          std::printf("colag_world: PX4 falls silent at %.1f s\n", t);
          break;
        case Px4Fault::kFailsafe:
          bridge_.fail_safe();
          std::printf("colag_world: PX4 fails safe (holds) at %.1f s\n", t);
          break;
        case Px4Fault::kPilot:
          bridge_.pilot_takes_over();
          std::printf("colag_world: a pilot switches PX4 to position mode at %.1f s\n", t);
          break;
        case Px4Fault::kNone:
          break;
      }
    }
    bridge_.step(now);
    if (!injected_ || reported_) return;
    const double since = t - fault_at_s_;
    bool still = true;
    for (int i = 0; i < world_.ugv_count(); ++i)
      still = still && std::abs(world_.ugv(i).speed_mps()) < ugv::kStillSpeed_mps;
    if (still || since > 5.0) {
      reported_ = true;
      std::printf(still ? "colag_world: every UGV stood still %.2f s after PX4's fault\n"
                        : "colag_world: UGVs still moving %.2f s after PX4's fault\n",
                  since);
    }
  }

 private:
  sim::Px4StackBridge& bridge_;
  const sim::SimWorld& world_;
  Px4Fault fault_;
  double fault_at_s_;
  bool injected_ = false, reported_ = false;
  TimePoint start_{};
};

// On PX4 the mission ends with a landing: the world and its PX4 run on (scripts/sitl.sh stops
// uav_fw when it reads the first line, and uav_fw lands) until PX4 disarms, at most 60 s.
void land_after_mission(const hal::Clock& clock, sim::SimWorld& world, Px4StackStep& px4_step,
                        const sim::Px4StackBridge& px4) {
  std::printf("colag_world: mission over; waiting for the UAV to land\n");
  std::fflush(stdout);
  const TimePoint start = clock.now();
  TimePoint last = start;
  while (px4.vehicle().armed() && clock.now() - start < std::chrono::seconds(60)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const TimePoint now = clock.now();
    if (now - last < std::chrono::milliseconds(10)) continue;
    world.step(now, std::min(to_seconds(now - last), 0.1));
    px4_step.step(now);
    last = now;
  }
  std::printf(px4.vehicle().armed()
                  ? "colag_world: the UAV did not land within 60 s\n"
                  : "colag_world: the UAV landed and PX4 disarmed %.1f s after the mission\n",
              to_seconds(clock.now() - start));
}

class BridgeStep final : public platform::Task {
 public:
  explicit BridgeStep(sim::WorldBridge& bridge) : bridge_(bridge) {}
  const char* name() const override { return "bridge"; }
  void step(TimePoint) override { bridge_.step(); }

 private:
  sim::WorldBridge& bridge_;
};

// What the world hears of the robots on their own domain.
struct RobotTraffic final : platform::SampleSink {
  RobotTraffic(int ugvs, const TruthHistory& truth)
      : status(static_cast<std::size_t>(ugvs)),
        heard(status.size()),
        nees(status.size()),
        truth_(truth) {}
  void on_sample(msg::Topic topic, const void* sample, TimePoint now) override {
    switch (topic) {
      case msg::topic_of<msg::UgvStatus>: {
        const auto& s = *static_cast<const msg::UgvStatus*>(sample);
        if (s.ugv_id < status.size()) {
          status[s.ugv_id] = s;
          heard[s.ugv_id] = now;
          add_nees(s);
        }
        break;
      }
      case msg::topic_of<msg::MapPatch>:
        ++patches;
        patch_bytes += static_cast<const msg::MapPatch*>(sample)->data.count;
        break;
      case msg::topic_of<msg::CollisionInfo>: {
        const auto& ci = *static_cast<const msg::CollisionInfo*>(sample);
        if (!ci.cancel && ci.ugv_id < status.size()) ++requests[ci.ugv_id];
        break;
      }
      case msg::topic_of<msg::UavOdometry>:
        uav_heard = now;
        break;
      default:
        break;
    }
  }
  // How honest a UGV's covariance is: NEES of its (x, y, yaw) against the truth, while it drives
  // (as colag_sim measures it).
  void add_nees(const msg::UgvStatus& s) {
    if (s.mode == msg::UgvMode::kWaitingForInit || s.mode == msg::UgvMode::kArrived) return;
    const std::optional<Pose2> truth = truth_.at(s.ugv_id, s.stamp);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> cov(s.covariance);
    if (!truth || !(cov.determinant() > 0.0)) return;
    const Pose2 estimate{Vec2(s.position_m[0], s.position_m[1]), s.yaw_rad};
    auto& [mean, n] = nees[s.ugv_id];
    mission::add_to_mean(mission::pose_nees(estimate, Mat3(cov), *truth), mean, n);
  }
  std::vector<msg::UgvStatus> status;
  std::vector<TimePoint> heard;                        // TimePoint{} = never
  std::vector<std::pair<double, std::uint64_t>> nees;  // mean, samples
  std::array<std::uint64_t, limits::kMaxUgvs> requests{};
  TimePoint uav_heard{};
  std::uint64_t patches = 0, patch_bytes = 0;

 private:
  const TruthHistory& truth_;
};

// Watches the mission every 100 ms: when it starts, who has arrived, when it is over.
class Monitor final : public platform::Task {
 public:
  Monitor(const mission::MissionConfig& cfg, sim::SimWorld& world, RobotTraffic& traffic,
          platform::RealtimeExecutor& exec, double start_timeout_s, double max_silence_s,
          bool quiet)
      : cfg_(cfg),
        world_(world),
        traffic_(traffic),
        exec_(exec),
        start_timeout_s_(start_timeout_s),
        max_silence_s_(max_silence_s),
        quiet_(quiet),
        reach_s_(static_cast<std::size_t>(cfg.ugvs), -1.0),
        reached_(reach_s_.size(), false),
        still_(reach_s_.size()) {}
  const char* name() const override { return "monitor"; }
  void step(TimePoint now) override {
    if (created_ == TimePoint{}) created_ = now;
    if (!started_) {
      bool all = traffic_.uav_heard != TimePoint{};
      for (const TimePoint h : traffic_.heard)
        all = all && h != TimePoint{};
      if (all) {
        started_ = true;
        t0_ = now;
        say("colag_world: every robot is up; mission clock started");
      } else if (to_seconds(now - created_) > start_timeout_s_) {
        failure_ = "not every robot appeared within the start timeout:" + missing();
        exec_.request_stop();
      }
      return;
    }
    const double t = to_seconds(now - t0_);
    if (last_ == TimePoint{}) last_ = now;
    bool all_done = true;
    int reached = 0;
    for (int i = 0; i < cfg_.ugvs; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (to_seconds(now - traffic_.heard[k]) > max_silence_s_) {
        failure_ = "UGV " + std::to_string(i) + "'s firmware went silent";
        exec_.request_stop();
        return;
      }
      // Arrived at its mission goal: a goal sent at run time (ROS 2 goal_pose) is a stop on
      // the way, not the end of its mission.
      const msg::UgvStatus& st = traffic_.status[k];
      const bool arrived =
          st.mode == msg::UgvMode::kArrived &&
          (Vec2(st.goal_m[0], st.goal_m[1]) - mission::ugv_goal(cfg_, i)).norm() < 0.01;
      still_[k].update(arrived, world_.ugv(i).speed_mps(), to_seconds(now - last_));
      if (arrived && reach_s_[k] < 0.0) {
        reach_s_[k] = t;
        reached_[k] =
            (world_.ugv(i).pose().p - mission::ugv_goal(cfg_, i)).norm() <= cfg_.goal_tolerance_m;
      }
      reached += reached_[k] ? 1 : 0;
      all_done = all_done && (arrived || world_.ugv(i).frozen());
    }
    if (!quiet_ && t >= next_report_s_) {
      next_report_s_ += 10.0;
      std::printf("colag_world: t = %5.1f s  reached %d/%d  collisions %zu\n", t, reached,
                  cfg_.ugvs, world_.collisions().size());
      std::fflush(stdout);
    }
    last_ = now;
    elapsed_s_ = t;
    if (all_done || t >= cfg_.max_time_s) exec_.request_stop();
  }

  std::string missing() const {
    std::string m;
    if (traffic_.uav_heard == TimePoint{}) m += " UAV";
    for (std::size_t i = 0; i < traffic_.heard.size(); ++i)
      if (traffic_.heard[i] == TimePoint{}) m += " UGV" + std::to_string(i);
    return m;
  }
  void say(const char* s) const {
    if (!quiet_) {
      std::printf("%s\n", s);
      std::fflush(stdout);
    }
  }

  const mission::MissionConfig& cfg_;
  sim::SimWorld& world_;
  RobotTraffic& traffic_;
  platform::RealtimeExecutor& exec_;
  double start_timeout_s_;
  double max_silence_s_;
  bool quiet_;
  bool started_ = false;
  TimePoint created_{}, t0_{};
  double elapsed_s_ = 0.0, next_report_s_ = 10.0;
  std::vector<double> reach_s_;
  std::vector<bool> reached_;
  std::vector<mission::StillCount> still_;  // waiting as a user sees it (truth_metrics.hpp)
  TimePoint last_{};
  std::string failure_;
};

int run(int argc, char** argv) {
  // Line-buffered even into a pipe or journald: a log must not lose its tail on SIGTERM.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CLI::App app{"colag_world: the simulated world for software-in-the-loop runs"};
  mission::MissionConfig cfg;
  std::string json_path;
  std::uint32_t domain = 0;
  double start_timeout_s = 60.0;
  double max_silence_s = 5.0;
  double time_scale = 1.0;
  bool quiet = false;
  bool print_sensors = false;
  std::string world_name = "ideal";
  std::string uav_stack = "sim";
  std::string px4_release = "1.16";
  double px4_silent_at = -1.0, px4_failsafe_at = -1.0, px4_pilot_at = -1.0;
  auto* scenario = app.add_option("--scenario", cfg.scenario, "sparse | dense | pillars | rooms")
                       ->check(CLI::IsMember(mission::kGeneratedScenarios));
  auto* map = app.add_option("--map", cfg.map_file, "a PCD map instead of a generated scenario");
  auto* ugvs = app.add_option("--ugvs", cfg.ugvs, "number of UGVs")
                   ->check(CLI::Range(1, static_cast<int>(limits::kMaxUgvs)));
  auto* site = sim::add_site_option(app, cfg.site)->excludes(map);
  std::string scenario_file;
  app.add_option("--scenario-file", scenario_file,
                 "a YAML scenario (colag_sim's, config/scenarios/README.md): map, starts, goals, "
                 "world; --seed, --world, --max-time given as well override it")
      ->excludes(scenario)
      ->excludes(map)
      ->excludes(ugvs)
      ->excludes(site)
      ->check(CLI::ExistingFile);
  bool print_placements = false;
  app.add_flag("--print-placements", print_placements,
               "print each UGV's start and goal (one line each: id x y yaw_rad goal_x goal_y, then "
               "any route points x y), exit");
  app.add_option("--seed", cfg.seed, "map seed")->check(sim::kSeed);
  app.add_option("--domain", domain, "the robots' DDS domain (the sim link uses domain + 1)")
      ->check(CLI::Range(0, 231));
  app.add_option("--max-time", cfg.max_time_s, "mission time limit, s")
      ->check(sim::positive_up_to(1e6));
  app.add_option("--start-timeout", start_timeout_s, "how long to wait for the robots, s")
      ->check(sim::positive_up_to(1e6));
  app.add_option("--max-silence", max_silence_s,
                 "a robot silent this long ends the run (exit 3), s (a restart takes longer)")
      ->check(sim::positive_up_to(1e6));
  app.add_option("--lidar-columns", cfg.lidar_columns, "LiDAR horizontal resolution")
      ->check(CLI::Range(60, static_cast<int>(limits::kMaxLidarColumns)));
  app.add_option("--json", json_path, "write the metrics (colag_sim's schema) here");
  app.add_option("--time-scale", time_scale,
                 "simulated seconds per second (the robots need the same --time-scale)")
      ->check(CLI::Range(0.1, 20.0));
  app.add_option("--world", world_name,
                 "ideal (the paper's), field (what real sensors do), or a YAML world file "
                 "(config/worlds/field.yaml); each robot's clock is the host's in SITL");
  sim::add_ugv_base_option(app, cfg.ugv_base);
  app.add_option("--uav-stack", uav_stack,
                 "sim: the UAV's devices over the sim link (robot.hal sim); px4: PX4's agent, "
                 "FAST-LIO and the Livox driver on their wire formats (robot.hal px4)")
      ->check(CLI::IsMember({"sim", "px4"}));
  app.add_option("--px4-release", px4_release, "the PX4 release played (1.15 | 1.16)")
      ->check(CLI::IsMember({"1.15", "1.16"}));
  app.add_option("--px4-silent-at", px4_silent_at,
                 "fault: PX4 (its agent) falls silent at this mission time, s")
      ->check(sim::positive_up_to(1e6));
  app.add_option("--px4-failsafe-at", px4_failsafe_at,
                 "fault: PX4 fails safe (holds, failsafe flag) at this mission time, s")
      ->check(sim::positive_up_to(1e6));
  app.add_option("--px4-pilot-at", px4_pilot_at,
                 "fault: a pilot switches PX4 to position mode at this mission time, s")
      ->check(sim::positive_up_to(1e6));
  app.add_flag("--print-uav-sensors", print_sensors,
               "print the uav.yaml sections describing the world's UAV LiDAR and camera, exit");
  app.add_flag("--quiet", quiet, "only errors");
  app.footer(
      "Exit codes: 0 the mission ran (its JSON says how it went); 1 DDS failed; 2 a usage or\n"
      "input error; 3 a robot never appeared or went silent.");
  if (const auto code = sim::parse_command_line(app, argc, argv)) return *code;
  if (!cfg.map_file.empty()) cfg.scenario = "file";
  if (const int code =
          sim::apply_scenario_options(app, "colag_world", scenario_file, world_name, cfg))
    return code;
  mission::lay_out_site(cfg);
  if (std::string error; !mission::check(cfg, error)) {
    std::fprintf(stderr, "colag_world: %s\n", error.c_str());
    return 2;
  }
  if (print_placements) {
    for (int i = 0; i < cfg.ugvs; ++i) {
      const Pose2 s0 = mission::ugv_start(cfg, i);
      const Vec2 g = mission::ugv_goal(cfg, i);
      std::printf("%d %.6f %.6f %.9f %.6f %.6f", i, s0.p.x(), s0.p.y(), s0.yaw_rad, g.x(), g.y());
      for (const Vec2& v : mission::ugv_via(cfg, i))
        std::printf(" %.6f %.6f", v.x(), v.y());  // the route's points before the goal
      std::printf("\n");
    }
    return 0;
  }
  const sim::SimWorldConfig wc = mission::sim_world_config(cfg);
  const bool px4 = uav_stack == "px4";
  const int faults = (px4_silent_at >= 0.0 ? 1 : 0) + (px4_failsafe_at >= 0.0 ? 1 : 0) +
                     (px4_pilot_at >= 0.0 ? 1 : 0);
  if (faults > 0 && !px4) {
    std::fprintf(stderr, "colag_world: PX4 faults need --uav-stack px4\n");
    return 2;
  }
  if (faults > 1) {
    std::fprintf(stderr, "colag_world: one PX4 fault per run\n");
    return 2;
  }
  const Px4Fault fault = px4_silent_at >= 0.0     ? Px4Fault::kSilent
                         : px4_failsafe_at >= 0.0 ? Px4Fault::kFailsafe
                         : px4_pilot_at >= 0.0    ? Px4Fault::kPilot
                                                  : Px4Fault::kNone;
  const double fault_at = std::max({px4_silent_at, px4_failsafe_at, px4_pilot_at});
  const std::uint32_t sim_domain = hal::sim::sim_domain_for(domain);
  sim::Px4StackConfig stack;
  stack.dds_domain = sim_domain;  // beside the sim link: the robots' domain sees none of it
  stack.release = hal::px4::parse_px4_release(px4_release).value();
  if (print_sensors) {
    print_uav_sensors(wc, px4 ? &stack : nullptr);
    return 0;
  }
  // Each process reads the host's clock: the world's sensor stamps must be on it too.
  if (cfg.world.clocks.offset_s != 0.0 || cfg.world.clocks.drift_ppm != 0.0)
    std::fprintf(stderr,
                 "colag_world: warning: the world's clock offsets and drifts are not simulated in "
                 "SITL (every robot reads this host's clock); colag_sim simulates them\n");
  if (!json_path.empty() && !std::ofstream(json_path)) {  // fail now, not after the mission
    std::fprintf(stderr, "colag_world: --json %s: cannot write there\n", json_path.c_str());
    return 2;
  }

  sim::BoxWorld boxes;
  std::string error;
  std::vector<std::string> warnings;
  if (!mission::build_world(cfg, boxes, error, &warnings)) {
    std::fprintf(stderr, "colag_world: %s\n", error.c_str());
    return 2;
  }
  for (const std::string& w : warnings)
    std::fprintf(stderr, "colag_world: warning: %s\n", w.c_str());
  platform::RealtimeExecutor exec(time_scale);
  platform::WorkerPool pool(1);
  sim::SimWorld world(wc, boxes, exec.clock(), &pool);
  std::vector<sim::WheelErrors> wheels = mission::draw_wheels(cfg);
  for (int i = 0; i < cfg.ugvs; ++i)
    world.add_ugv(mission::ugv_start(cfg, i), {}, &wheels[static_cast<std::size_t>(i)]);
  // On PX4 the UAV takes off from the ground through the offboard protocol.
  const Vec3 uav_start = cfg.uav_start;
  world.add_uav(px4 ? Vec3(uav_start.x(), uav_start.y(), 0.05) : uav_start);

  hal::sim::SimLink link;
  if (const Status s = link.init(sim_domain, hal::sim::SimLink::Side::kWorld); !s) {
    std::fprintf(stderr, "colag_world: sim link on DDS domain %u: %s (%s)\n", sim_domain,
                 s.message(), dds_strretcode(link.last_error()));
    return 1;
  }
  sim::WorldBridge bridge(link, world, true, px4);
  sim::Px4StackBridge px4_bridge(world);
  if (px4) {
    if (std::string stack_error; !px4_bridge.init(stack, stack_error)) {
      std::fprintf(stderr, "colag_world: %s\n", stack_error.c_str());
      return 1;
    }
  }
  Px4StackStep px4_step(px4_bridge, world, fault, fault_at);
  platform::dds::DdsTransport dds;
  platform::dds::DdsConfig dds_cfg;
  dds_cfg.domain_id = domain;
  dds_cfg.publish_only<>();  // a listener only
  TruthHistory truth(cfg.ugvs);
  RobotTraffic traffic(cfg.ugvs, truth);
  Status st = dds.init(dds_cfg);
  for (msg::Topic t : {msg::topic_of<msg::UgvStatus>, msg::topic_of<msg::MapPatch>,
                       msg::topic_of<msg::CollisionInfo>, msg::topic_of<msg::UavOdometry>})
    if (st) st = dds.subscribe(t, kAnyRobot, traffic);
  if (!st) {
    std::fprintf(stderr, "colag_world: DDS domain %u: %s (%s)\n", domain, st.message(),
                 dds_strretcode(dds.last_error()));
    return 1;
  }

  WorldStep world_step(world, truth);
  BridgeStep bridge_step(bridge);
  platform::TransportPump pump(dds);
  Monitor monitor(cfg, world, traffic, exec, start_timeout_s, max_silence_s, quiet);
  st = exec.add({&bridge_step, 10ms, 5ms});
  if (st && px4) st = exec.add({&px4_step, 10ms, 5ms});
  if (st) st = exec.add({&world_step, 20ms, 15ms});
  if (st) st = exec.add({&pump, 10ms, 5ms});
  if (st) st = exec.add({&monitor, 100ms, 5ms});
  if (st) st = exec.init();
  if (!st) {
    std::fprintf(stderr, "colag_world: start-up: %s\n", st.message());
    return 1;
  }
  if (!quiet)
    std::printf(
        "colag_world: %s, %d UGVs, seed %llu, %s world; robots on DDS domain %u, sim link on "
        "%u%s%s\n",
        cfg.scenario.c_str(), cfg.ugvs, static_cast<unsigned long long>(cfg.seed),
        cfg.world.name.c_str(), domain, sim_domain, px4 ? "; the UAV on PX4 " : "",
        px4 ? px4_release.c_str() : "");
  std::fflush(stdout);
  const auto wall_start = std::chrono::steady_clock::now();
  exec.run_until(TimePoint::max());

  if (!monitor.failure_.empty()) {
    std::fprintf(stderr, "colag_world: %s\n", monitor.failure_.c_str());
    return 3;
  }
  // The outcome, as colag_sim reports it.
  mission::MissionOutcome out;
  out.config = cfg;
  out.sim_time_s = monitor.elapsed_s_;
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  int reached = 0;
  for (int i = 0; i < cfg.ugvs; ++i) {
    const auto k = static_cast<std::size_t>(i);
    mission::UgvOutcome o;
    o.id = i;
    o.reached = monitor.reached_[k];
    o.reach_time_s = o.reached ? monitor.reach_s_[k] : -1.0;
    o.waiting_time_s = traffic.status[k].waiting_time_s;
    o.stopped_s = monitor.still_[k].stopped_s;
    o.stops = monitor.still_[k].stops;
    std::tie(o.nees_mean, o.nees_samples) = traffic.nees[k];
    o.final_mode = traffic.status[k].mode;
    if (o.final_mode == msg::UgvMode::kBlocked) o.blocked_reason = traffic.status[k].blocked_reason;
    o.support_requests = traffic.requests[k];
    reached += o.reached ? 1 : 0;
    out.ugvs.push_back(o);
  }
  mission::summarise(world, out);
  out.uav_traj_length_m = world.uav().travelled_m();
  out.map_patches = traffic.patches;
  out.map_patch_bytes = traffic.patch_bytes;
  const std::string json = mission::to_json(out);
  if (!json_path.empty()) {
    std::ofstream out_file(json_path);
    out_file << json << "\n";
    if (!out_file.flush()) {
      std::fprintf(stderr, "colag_world: --json %s: cannot write there\n", json_path.c_str());
      return 2;
    }
  }
  const auto& b = bridge.counters();
  if (!quiet) {
    std::printf(
        "colag_world: mission over after %.1f s: reached %d/%d, collisions %d, mean reach time "
        "%.1f s, mean waiting %.1f s\n",
        out.sim_time_s, reached, cfg.ugvs, out.collisions, out.reach_time_s, out.waiting_time_s);
    std::printf(
        "colag_world: sim link: %llu CAN frames to robots, %llu from them, %llu setpoints, %llu "
        "scans (%.1f MB), %llu camera frames\n",
        static_cast<unsigned long long>(b.frames_to_robots),
        static_cast<unsigned long long>(b.frames_from_robots),
        static_cast<unsigned long long>(b.setpoints), static_cast<unsigned long long>(b.scans),
        static_cast<double>(b.scan_bytes) / 1e6, static_cast<unsigned long long>(b.rpe_frames));
    if (px4) {
      const sim::Px4StackCounters& c = px4_bridge.counters();
      std::printf(
          "colag_world: PX4: %llu offboard heartbeats, %llu setpoints, %llu commands; %llu "
          "statuses, %llu odometry, %llu clouds out\n",
          static_cast<unsigned long long>(c.heartbeats),
          static_cast<unsigned long long>(c.setpoints), static_cast<unsigned long long>(c.commands),
          static_cast<unsigned long long>(c.statuses), static_cast<unsigned long long>(c.odometry),
          static_cast<unsigned long long>(c.clouds));
    }
    if (!json_path.empty()) std::printf("colag_world: metrics in %s\n", json_path.c_str());
  }
  if (px4 && fault == Px4Fault::kNone)
    land_after_mission(exec.clock(), world, px4_step, px4_bridge);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return colag::sim::guarded_main("colag_world", 1, [&] { return run(argc, argv); });
}
