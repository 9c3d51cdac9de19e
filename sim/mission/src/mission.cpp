#include "colag/sim/mission/mission.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>

#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/platform/lane_outbox.hpp"
#include "colag/platform/lockstep_executor.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/monotonic_clock.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/world/pcd_loader.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "colag/uav/map_sharer.hpp"
#include "colag/uav/mapper.hpp"
#include "colag/uav/uav_supervisor_task.hpp"
#include "colag/ugv/ugv_nav_task.hpp"

namespace colag::mission {

using namespace std::chrono_literals;

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
constexpr double kStartY = 16.0, kGoalY = -16.0;

// UGV i's lane: x = 0, -2, 2, -4, 4, ...
double lane_x(int i) {
  return (i % 2 == 1 ? -2.0 : 2.0) * ((i + 1) / 2);
}

// The faults in force at simulated time t (checked every 100 ms of the run).
void apply_faults(const FaultConfig& fc, double t, platform::LoopbackTransport& bus) {
  if (!fc.any()) return;
  platform::LinkFaults base;
  base.drop_probability = fc.loss;
  base.latency = seconds(fc.latency_ms / 1e3);
  base.jitter = seconds(fc.jitter_ms / 1e3);
  platform::LinkFaults lost = base;
  lost.drop_probability = 1.0;
  const bool uav_out = fc.uav_blackout.contains(t);
  const bool rpe_out = uav_out || fc.rpe_blackout.contains(t);
  for (std::size_t i = 0; i < msg::kTopicCount; ++i) {
    const auto topic = static_cast<msg::Topic>(i);
    const bool from_uav = topic == msg::Topic::kUavOdometry || topic == msg::Topic::kRelativePose ||
                          topic == msg::Topic::kMapPatch || topic == msg::Topic::kSupportPlan;
    const bool out = topic == msg::Topic::kRelativePose ? rpe_out : (from_uav && uav_out);
    bus.set_faults(topic, out ? lost : base);
  }
}

class WorldTask final : public platform::Task {
 public:
  explicit WorldTask(sim::SimWorld& world) : world_(world) {}
  const char* name() const override { return "world"; }
  void step(TimePoint now) override { world_.step(now, 0.02); }

 private:
  sim::SimWorld& world_;
};

// Self-perception baseline: a fixed reference frame at the origin stands in for the UAV, so the
// UGV's own estimator gets its true pose; each UGV maps with its own LiDAR.
class ReferenceFrameTask final : public platform::Task {
 public:
  explicit ReferenceFrameTask(platform::Transport& t) : transport_(t) {}
  const char* name() const override { return "reference"; }
  void step(TimePoint now) override {
    msg::UavOdometry od;
    od.stamp = now;
    (void)transport_.publish(od);
  }

 private:
  platform::Transport& transport_;
};

class SelfPerceptionTask final : public platform::Task {
 public:
  SelfPerceptionTask(platform::Transport& t, sim::SimWorld& world, int id)
      : transport_(t), world_(world), id_(id), mapper_(std::make_unique<uav::Mapper>()) {}
  const char* name() const override { return "self_perception"; }
  void step(TimePoint now) override {
    const Pose2& g = world_.ugv(id_).pose();
    hal::LidarScanView scan;
    if (world_.ugv_lidar(id_).poll(scan)) {
      mapper_->insert_scan({Vec3(g.p.x(), g.p.y(), 0.4), quat_from_yaw(g.yaw_rad)}, scan);
    }
    msg::RelativePose rp;  // the true pose, relative to the reference frame
    rp.stamp = now;
    rp.ugv_id = static_cast<RobotId>(id_);
    rp.position_m[0] = g.p.x();
    rp.position_m[1] = g.p.y();
    const Quat q = quat_from_yaw(g.yaw_rad);
    rp.orientation_wxyz[0] = q.w();
    rp.orientation_wxyz[3] = q.z();
    rp.covariance[0] = rp.covariance[5] = rp.covariance[10] = 1e-4;
    rp.covariance[15] = 1e-5;
    (void)transport_.publish(rp);
    msg::MapPatch patch;
    if (sharer_.due(static_cast<RobotId>(id_), now) &&
        sharer_.make_patch(*mapper_, g.p, g.yaw_rad, world_.ugv(id_).speed_mps(), patch) &&
        sharer_.should_send(static_cast<RobotId>(id_), now, patch)) {
      patch.stamp = now;
      patch.ugv_id = static_cast<RobotId>(id_);
      (void)transport_.publish(patch);
    }
  }

 private:
  platform::Transport& transport_;
  sim::SimWorld& world_;
  int id_;
  std::unique_ptr<uav::Mapper> mapper_;
  uav::MapSharer sharer_;
};

// After the UGV lanes ran: their samples go onto the bus in lane order, as if the UGVs' tasks
// had run one after the other.
class FlushOutboxes final : public platform::LaneBarrier {
 public:
  void lanes_done(TimePoint) override {
    for (platform::LaneOutbox* o : outboxes)
      o->flush();
  }
  std::vector<platform::LaneOutbox*> outboxes;
};

// Listens to the support requests (for the figure and the per-UGV counts).
class SupportLog final : public platform::SampleSink {
 public:
  explicit SupportLog(int ugvs)
      : requests(static_cast<std::size_t>(ugvs), 0), last(static_cast<std::size_t>(ugvs)) {}
  void on_sample(msg::Topic, const void* sample, TimePoint) override {
    const auto& ci = *static_cast<const msg::CollisionInfo*>(sample);
    if (ci.cancel || ci.ugv_id >= requests.size()) return;
    ++requests[ci.ugv_id];
    const Vec2 p(ci.support_point_m[0], ci.support_point_m[1]);
    auto& prev = last[ci.ugv_id];
    if (!prev || (*prev - p).norm() > 0.5) {
      prev = p;
      if (trace != nullptr) trace->support_points.push_back({ci.ugv_id, p});
    }
  }
  std::vector<std::uint64_t> requests;
  std::vector<std::optional<Vec2>> last;
  MissionTrace* trace = nullptr;
};

}  // namespace

bool build_world(const MissionConfig& cfg, sim::BoxWorld& world, std::string& error) {
  if (cfg.scenario == "sparse" || cfg.scenario == "dense") {
    sim::MapGenConfig gen;
    gen.boxes = cfg.scenario == "sparse" ? 40 : 80;
    gen.seed = cfg.seed;
    auto w = sim::generate_box_world(gen);
    if (!w) {
      error = w.status().message();
      return false;
    }
    world = w.value();
    return true;
  }
  if (cfg.scenario == "file") {
    std::vector<Vec3> points;
    if (!sim::load_pcd(cfg.map_file, points, error)) return false;
    world = sim::box_world_from_points(points);
    return true;
  }
  error = "unknown scenario '" + cfg.scenario + "' (sparse, dense, or a map file)";
  return false;
}

Pose2 ugv_start(int i) {
  return {Vec2(lane_x(i), kStartY), -M_PI / 2};
}
Vec2 ugv_goal(int i) {
  return Vec2(lane_x(i), kGoalY);
}
Vec3 uav_start() {
  return kUavStart;
}

Result<MissionOutcome> run_mission(const MissionConfig& cfg, MissionTrace* trace,
                                   std::string* error_out) {
  std::string error;
  const auto fail = [&](const std::string& e) {
    if (error_out != nullptr) *error_out = e;
    return Status{Errc::kInvalidArgument, "mission configuration"};
  };
  if (cfg.ugvs < 1 || cfg.ugvs > static_cast<int>(limits::kMaxUgvs)) {
    return fail("--ugvs must be in 1.." + std::to_string(limits::kMaxUgvs));
  }
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
  sim::BoxWorld boxes;
  if (!build_world(cfg, boxes, error)) return fail(error);

  const auto wall_start = std::chrono::steady_clock::now();
  platform::MonotonicClock stopwatch;
  auto ex = std::make_unique<platform::LockstepExecutor>(TimePoint{}, &stopwatch);
  auto bus = std::make_unique<platform::LoopbackTransport>(cfg.seed);
  sim::SimWorldConfig wc;
  wc.seed = cfg.seed;
  wc.lidar.columns = cfg.lidar_columns;
  wc.ugv.encoder_bias = fc.odom_bias;
  platform::WorkerPool pool(cfg.threads - 1);
  auto world = std::make_unique<sim::SimWorld>(wc, boxes, ex->clock(), &pool);
  WorldTask world_task(*world);
  platform::TransportPump pump(*bus);
  Status st = ex->add({&pump, 10ms, 2ms});
  if (st) st = ex->add({&world_task, 20ms, 20ms});

  // The UAV (not in the self-perception baseline).
  std::unique_ptr<uav::UavSupervisorTask> uav;
  std::unique_ptr<ReferenceFrameTask> reference;
  if (!cfg.self_perception) {
    world->add_uav(uav_start());
    uav::UavSupervisorConfig uc;
    if (cfg.ablation == Ablation::kNoScheduling)
      uc.scheduler.mode = uav::ScheduleMode::kNoScheduling;
    if (cfg.ablation == Ablation::kNoTimeWindows)
      uc.scheduler.mode = uav::ScheduleMode::kNoTimeWindows;
    uav = std::make_unique<uav::UavSupervisorTask>(uc, *bus, world->uav(), world->uav_lidar(),
                                                   world->uav_camera(), world->uav(), &pool);
  } else {
    reference = std::make_unique<ReferenceFrameTask>(*bus);
  }

  // The UGVs, each behind its own CAN link, each publishing through its own outbox: a UGV's
  // tasks are a lane of the executor, the UGVs' lanes run side by side on the worker pool.
  struct UgvStack {
    std::unique_ptr<platform::LaneOutbox> outbox;
    std::unique_ptr<hal::can::CanWheelOdometry> odometry;
    std::unique_ptr<hal::can::CanDrive> drive;
    std::unique_ptr<ugv::UgvNavTask> task;
    std::unique_ptr<SelfPerceptionTask> perception;
    Vec2 goal;
  };
  std::vector<UgvStack> ugvs(static_cast<std::size_t>(cfg.ugvs));
  for (int i = 0; i < cfg.ugvs; ++i) {
    world->add_ugv(ugv_start(i));
  }
  if (cfg.self_perception) world->enable_ugv_lidars();
  for (int i = 0; i < cfg.ugvs; ++i) {
    UgvStack& s = ugvs[static_cast<std::size_t>(i)];
    s.goal = ugv_goal(i);
    ugv::UgvNavConfig nc;
    nc.id = static_cast<RobotId>(i);
    nc.goal = s.goal;
    nc.has_start_guess = true;
    nc.start_guess = ugv_start(i);
    nc.use_rpe_updates = cfg.ablation != Ablation::kNoRpe;
    nc.predictor.use_uncertainty = cfg.ablation != Ablation::kNoUncertainty;
    nc.predictor.horizon_m = cfg.predict_horizon_m;
    nc.map.unknown_blocks_prediction = !cfg.self_perception;
    s.odometry = std::make_unique<hal::can::CanWheelOdometry>(world->ugv_can(i), wc.ugv.protocol,
                                                              wc.ugv.geometry);
    s.drive =
        std::make_unique<hal::can::CanDrive>(world->ugv_can(i), wc.ugv.protocol, wc.ugv.geometry);
    s.outbox = std::make_unique<platform::LaneOutbox>(*bus);
    s.task = std::make_unique<ugv::UgvNavTask>(nc, *s.outbox, *s.odometry, *s.drive);
    if (cfg.self_perception)
      s.perception = std::make_unique<SelfPerceptionTask>(*s.outbox, *world, i);
  }
  FlushOutboxes flush;
  for (const UgvStack& s : ugvs)
    flush.outboxes.push_back(s.outbox.get());
  ex->set_lanes(&pool, &flush);

  // The executor table: transport, world, UAV loops, then each UGV's loops in its own lane.
  // The UGVs plan at the same instants (each has its own computer: nothing keeps their loops
  // apart, and the firmware must be safe when they line up), so the lanes plan side by side.
  if (uav) {
    if (st) st = ex->add({&uav->control_loop(), 20ms, 5ms});
    if (st) st = ex->add({&uav->mapping_loop(), 100ms, 20ms});
    if (st) st = ex->add({&uav->sharing_loop(), 50ms, 5ms});
    if (st) st = ex->add({&uav->scheduling_loop(), 100ms, 10ms});
  }
  if (reference && st) st = ex->add({reference.get(), 20ms, 1ms});
  for (int i = 0; i < cfg.ugvs && st; ++i) {
    UgvStack& s = ugvs[static_cast<std::size_t>(i)];
    const int lane = i + 1;
    st = ex->add({&s.task->control_loop(), 20ms, 2ms, Duration{}, lane});
    if (st) st = ex->add({&s.task->planning_loop(), 100ms, 10ms, Duration{}, lane});
    if (st && s.perception) st = ex->add({s.perception.get(), 50ms, 10ms, Duration{}, lane});
  }
  SupportLog support(cfg.ugvs);
  support.trace = trace;
  if (st) st = bus->subscribe(msg::Topic::kCollisionInfo, kAnyRobot, support);
  if (st) st = ex->init();
  if (!st) return fail(std::string("cannot build the mission: ") + st.message());

  if (trace != nullptr) {
    *trace = MissionTrace{};
    trace->world = world->world();
    trace->ugv_paths.resize(ugvs.size());
    trace->ugv_ellipses.resize(ugvs.size());
    for (const auto& s : ugvs)
      trace->goals.push_back(s.goal);
  }

  // Run, watching the truth every 100 ms.
  MissionOutcome out;
  out.config = cfg;
  out.config.progress = nullptr;
  out.ugvs.resize(ugvs.size());
  const TimePoint end = time_at_seconds(cfg.max_time_s);
  int tick = 0;
  std::vector<int> open_stops(ugvs.size(), -1);  // index of each UGV's current stop in the trace
  while (ex->now() < end) {
    apply_faults(fc, to_seconds(ex->now()), *bus);
    ex->run_until(ex->now() + 100ms);
    ++tick;
    const double t = to_seconds(ex->now());
    bool all_done = true;
    for (std::size_t i = 0; i < ugvs.size(); ++i) {
      const ugv::UgvNavTask& task = *ugvs[i].task;
      UgvOutcome& o = out.ugvs[i];
      const sim::UgvBody& body = world->ugv(static_cast<int>(i));
      if (task.mode() == msg::UgvMode::kWaitingForInit) o.init_wait_s += 0.1;
      if (trace != nullptr) {
        const bool stopped = task.mode() == msg::UgvMode::kWaitingForSupport ||
                             task.mode() == msg::UgvMode::kWaitingForInit;
        const bool for_support = task.mode() == msg::UgvMode::kWaitingForSupport;
        auto& open = open_stops[i];
        if (stopped && open < 0) {
          open = static_cast<int>(trace->stops.size());
          trace->stops.push_back({static_cast<int>(i), t - 0.1, t, body.pose().p, for_support});
        } else if (stopped) {
          trace->stops[static_cast<std::size_t>(open)].to_s = t;
        } else {
          open = -1;
        }
      }
      const bool arrived = task.mode() == msg::UgvMode::kArrived;
      if (arrived && o.reach_time_s < 0.0) {
        o.reach_time_s = t;
        o.reached = (body.pose().p - ugvs[i].goal).norm() <= cfg.goal_tolerance_m;
      }
      all_done = all_done && (arrived || body.frozen());
      if (trace != nullptr && tick % 5 == 0) {
        const bool init = task.estimator().initialized();
        trace->ugv_paths[i].push_back(
            {t, body.pose().p, init ? task.estimator().pose().p : body.pose().p, init});
        if (tick % 50 == 0 && init && !arrived) {
          trace->ugv_ellipses[i].push_back(
              {task.estimator().pose().p, task.estimator().covariance().topLeftCorner<2, 2>()});
        }
      }
    }
    if (trace != nullptr && uav && tick % 5 == 0)
      trace->uav_path.push_back(world->uav().state().pose.p.head<2>());
    if (cfg.progress && tick % 10 == 0) cfg.progress(t / cfg.max_time_s);
    if (all_done) break;
  }

  // Outcome.
  for (std::size_t i = 0; i < ex->schedule().size(); ++i) {
    const platform::TaskStats& stats = ex->schedule().stats(i);
    auto it = std::find_if(out.task_times.begin(), out.task_times.end(),
                           [&](const TaskTime& t) { return t.name == stats.name; });
    if (it == out.task_times.end()) it = out.task_times.insert(it, TaskTime{stats.name});
    it->steps += stats.steps;
    it->total_s += to_seconds(stats.total_step);
    it->longest_ms = std::max(it->longest_ms, to_seconds(stats.longest_step) * 1e3);
  }
  out.sim_time_s = to_seconds(ex->now());
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  for (std::size_t i = 0; i < ugvs.size(); ++i) {
    UgvOutcome& o = out.ugvs[i];
    o.id = static_cast<int>(i);
    o.waiting_time_s = ugvs[i].task->waiting_time_s();
    o.support_requests = support.requests[i];
    if (!o.reached) o.reach_time_s = -1.0;
  }
  summarise(*world, out);
  if (uav) {
    out.uav_traj_length_m = world->uav().travelled_m();
    out.map_patches = uav->sharer().counters().patches;
    out.map_patch_bytes = uav->sharer().counters().bytes;
    out.schedules = uav->health().schedules;
    out.schedules_exact = uav->health().schedules_exact;
  }
  if (trace != nullptr) {
    for (const auto& c : world->collisions())
      trace->collisions.push_back(c.where);
    if (uav) {
      const auto& g = uav->mapper().geometry();
      const sim::BoxWorld& w = world->world();
      const CellIndex lo =
          g.layer().cell_of(Vec2(std::max(w.min_x_m, -18.0), std::max(w.min_y_m, -18.0)));
      const CellIndex hi =
          g.layer().cell_of(Vec2(std::min(w.max_x_m, 18.0), std::min(w.max_y_m, 18.0)));
      for (int y = std::max(lo.y, 0); y <= std::min(hi.y, g.cells_y() - 1); ++y) {
        for (int x = std::max(lo.x, 0); x <= std::min(hi.x, g.cells_x() - 1); ++x) {
          if (uav->sharer().classify(uav->mapper(), x, y) == CellState::kUnknown) {
            trace->unknown_cells.push_back(g.layer().center_of({x, y}));
          }
        }
      }
    }
  }
  return out;
}

void summarise(const sim::SimWorld& world, MissionOutcome& out) {
  double reach_sum = 0.0;
  int reached = 0;
  const auto n = static_cast<double>(out.ugvs.size());
  for (UgvOutcome& o : out.ugvs) {
    o.traj_length_m = world.ugv(o.id).travelled_m();
    o.min_clearance_m = world.min_clearance_m(o.id);
    for (const auto& c : world.collisions())
      o.collided = o.collided || c.ugv == o.id || c.other_ugv == o.id;
    if (o.reached) {
      reach_sum += o.reach_time_s;
      ++reached;
    }
    out.waiting_time_s += o.waiting_time_s / n;
    out.max_waiting_time_s = std::max(out.max_waiting_time_s, o.waiting_time_s);
    out.ugv_traj_length_m += o.traj_length_m / n;
  }
  out.reach_time_s = reached > 0 ? reach_sum / reached : -1.0;
  out.all_reached = reached == static_cast<int>(out.ugvs.size());
  out.collisions = static_cast<int>(world.collisions().size());
}

std::string to_json(const MissionOutcome& o, bool include_wall_time) {
  nlohmann::ordered_json j;
  j["seed"] = o.config.seed;
  if (o.config.faults.any()) {
    const FaultConfig& f = o.config.faults;
    j["faults"] = {{"loss", f.loss},
                   {"latency_ms", f.latency_ms},
                   {"jitter_ms", f.jitter_ms},
                   {"uav_blackout_s", {f.uav_blackout.from_s, f.uav_blackout.to_s}},
                   {"rpe_blackout_s", {f.rpe_blackout.from_s, f.rpe_blackout.to_s}},
                   {"odom_bias", f.odom_bias}};
  }
  j["scenario"] = o.config.scenario == "file" ? o.config.map_file : o.config.scenario;
  j["ablation"] = to_string(o.config.ablation);
  j["self_perception"] = o.config.self_perception;
  nlohmann::ordered_json ugvs = nlohmann::ordered_json::array();
  for (const UgvOutcome& u : o.ugvs) {
    nlohmann::ordered_json ju;
    ju["id"] = u.id;
    ju["reached"] = u.reached;
    ju["collided"] = u.collided;
    ju["reach_time_s"] =
        u.reached ? nlohmann::ordered_json(u.reach_time_s) : nlohmann::ordered_json(nullptr);
    ju["waiting_time_s"] = u.waiting_time_s;
    ju["init_wait_s"] = u.init_wait_s;
    ju["traj_length_m"] = u.traj_length_m;
    ju["min_clearance_m"] = u.min_clearance_m;
    ju["support_requests"] = u.support_requests;
    ugvs.push_back(ju);
  }
  j["ugvs"] = ugvs;
  nlohmann::ordered_json s;
  s["reach_time_s"] = o.reach_time_s >= 0.0 ? nlohmann::ordered_json(o.reach_time_s)
                                            : nlohmann::ordered_json(nullptr);
  s["waiting_time_s"] = o.waiting_time_s;
  s["max_waiting_time_s"] = o.max_waiting_time_s;
  s["ugv_traj_length_m"] = o.ugv_traj_length_m;
  s["uav_traj_length_m"] = o.uav_traj_length_m;
  s["collisions"] = o.collisions;
  s["all_reached"] = o.all_reached;
  j["summary"] = s;
  j["sim_time_s"] = o.sim_time_s;
  if (include_wall_time) {
    j["wall_time_s"] = o.wall_time_s;
    j["realtime_factor"] = o.wall_time_s > 0.0 ? o.sim_time_s / o.wall_time_s : 0.0;
  }
  j["map_patches"] = o.map_patches;
  j["map_patch_bytes"] = o.map_patch_bytes;
  j["schedules"] = o.schedules;
  j["schedules_exact"] = o.schedules_exact;
  return j.dump(2);
}

}  // namespace colag::mission
