#include "colag/sim/mission/mission.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "colag/hal/can/can_base.hpp"
#include "colag/platform/lane_outbox.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/monotonic_clock.hpp"
#include "colag/platform/worker_pool.hpp"
#include "colag/sim/mission/reboot_link.hpp"
#include "colag/sim/mission/truth_metrics.hpp"
#include "colag/sim/mission/world_setup.hpp"
#include "colag/sim/world/sim_world.hpp"
#include "colag/uav/clock_server.hpp"
#include "colag/uav/map_sharer.hpp"
#include "colag/uav/mapper.hpp"
#include "colag/uav/nearby_relay.hpp"
#include "colag/uav/team_filter.hpp"
#include "colag/uav/uav_supervisor_task.hpp"
#include "colag/ugv/ugv_nav_task.hpp"

namespace colag::mission {

using namespace std::chrono_literals;

namespace {

// The faults in force at simulated time t (checked every 100 ms of the run).
void apply_faults(const FaultConfig& fc, double t, platform::LoopbackTransport& bus) {
  if (!fc.any()) return;
  platform::LinkFaults base;
  base.drop_probability = fc.loss;
  base.latency = seconds(fc.latency_ms / 1e3);
  base.jitter = seconds(fc.jitter_ms / 1e3);
  platform::LinkFaults lost = base;
  lost.drop_probability = 1.0;
  const bool all_out = fc.blackout.contains(t);
  const bool uav_out = all_out || fc.uav_blackout.contains(t);
  const bool rpe_out = uav_out || fc.rpe_blackout.contains(t);
  for (std::size_t i = 0; i < msg::kTopicCount; ++i) {
    const auto topic = static_cast<msg::Topic>(i);
    const bool from_uav =
        topic == msg::topic_of<msg::UavOdometry> || topic == msg::topic_of<msg::RelativePose> ||
        topic == msg::topic_of<msg::MapPatch> || topic == msg::topic_of<msg::SupportPlan>;
    const bool out =
        all_out || (topic == msg::topic_of<msg::RelativePose> ? rpe_out : (from_uav && uav_out));
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
// UGV's own estimator gets its true pose; each UGV maps with its own LiDAR. The UGVs hear of
// each other as they do with a UAV: their statuses, relayed to each UGV every 100 ms
// (uav/nearby_relay.hpp); without it they planned and predicted blind to each other and drove
// into each other.
class ReferenceFrameTask final : public platform::Task {
 public:
  explicit ReferenceFrameTask(platform::Transport& t) : transport_(t) {}
  const char* name() const override { return "reference"; }
  Status init(TimePoint) override {
    if (Status s = clock_.attach(transport_, 0); !s) return s;
    return statuses_in_.attach(transport_);
  }
  void step(TimePoint now) override {
    clock_.step(now);  // the UGVs' fleet time is this stand-in's clock
    msg::UavOdometry od;
    od.stamp = now;
    (void)transport_.publish(od);
    msg::UgvStatus s;
    while (statuses_in_.pop(s)) {
      if (s.ugv_id < limits::kMaxUgvs) ugvs_[s.ugv_id] = {true, now, s};
    }
    if (!elapsed(now, relayed_, 100ms)) return;
    relayed_ = now;
    const uav::UavSupervisorConfig relay;  // the UAV's relay settings
    (void)uav::relay_nearby(
        ugvs_, now, relay.status_timeout, relay.nearby, passes_++, nearby_,
        [&](const msg::NearbyUgvs& m) { return static_cast<bool>(transport_.publish(m)); });
  }

 private:
  struct Ugv {
    bool known = false;
    TimePoint heard{};
    msg::UgvStatus status;
  };
  platform::Transport& transport_;
  uav::ClockServer clock_;
  platform::QueueReader<msg::UgvStatus, 4 * limits::kMaxUgvs> statuses_in_;
  std::array<Ugv, limits::kMaxUgvs> ugvs_{};
  msg::NearbyUgvs nearby_;
  std::uint64_t passes_ = 0;
  TimePoint relayed_ = kNever;
};

class SelfPerceptionTask final : public platform::Task {
 public:
  SelfPerceptionTask(platform::Transport& t, sim::SimWorld& world, int id,
                     const uav::LidarBeamPattern& pattern)
      : transport_(t),
        world_(world),
        id_(id),
        mapper_(std::make_unique<uav::Mapper>()),
        no_returns_(pattern) {}
  const char* name() const override { return "self_perception"; }
  void step(TimePoint now) override {
    const Pose2& g = world_.ugv(id_).pose();
    hal::LidarScanView scan;
    if (world_.ugv_lidar(id_).poll(scan)) {
      // The other UGVs, where they truly are (this baseline knows true poses), are kept out of
      // its map as the UAV keeps them out of its own.
      team_.begin();
      for (int j = 0; j < world_.ugv_count(); ++j) {
        const sim::UgvBody& other = world_.ugv(j);
        (void)team_.add(static_cast<std::size_t>(j), other.pose().p, 0.0, Duration::zero(),
                        other.pose().yaw_rad, other.speed_mps());
      }
      const Pose3 sensor{Vec3(g.p.x(), g.p.y(), 0.4), quat_from_yaw(g.yaw_rad)};
      const double ground = mapper_->geometry().origin_z();
      mapper_->insert_scan(
          sensor, team_.apply(no_returns_.complete(scan, sensor, ground), sensor, *mapper_));
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
  uav::NoReturnBeams no_returns_;
  uav::TeamFilter team_;
  uav::MapSharer sharer_;
};

// A robot's loop on the robot's own clock: the executor releases it on the world's time, the loop
// sees its board's time (as it would on the board).
class OnRobotClock final : public platform::Task {
 public:
  OnRobotClock(platform::Task& inner, const sim::ClockModel& clock)
      : inner_(inner), clock_(clock) {}
  const char* name() const override { return inner_.name(); }
  Status init(TimePoint now) override { return inner_.init(clock_.local(now)); }
  void step(TimePoint now) override { inner_.step(clock_.local(now)); }
  void on_overrun(Duration d) override { inner_.on_overrun(d); }

 private:
  platform::Task& inner_;
  sim::ClockModel clock_;
};

// Each robot's clock: UAV 0's (fleet time) first, then one per UGV, then UAV 1's, 2's, ... (see
// ClockConfig; drawn in that order, so that adding UAVs leaves the UGVs' clocks as they were).
std::vector<sim::ClockModel> draw_clocks(const MissionConfig& cfg) {
  ClockConfig c = cfg.clocks;
  if (!c.any()) {  // the world's
    c.offset_s = cfg.world.clocks.offset_s;
    c.drift_ppm = cfg.world.clocks.drift_ppm;
  }
  std::vector<sim::ClockModel> out(static_cast<std::size_t>(cfg.ugvs + std::max(cfg.uavs, 1)));
  if (!c.any()) return out;
  Rng rng(cfg.seed * 0x9E3779B97F4A7C15ULL + 0xC10C);  // its own stream: the rest is unchanged
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double base = rng.uniform(-c.offset_s, c.offset_s);
    out[i].offset_s = i == 0 ? c.offset_s : c.offset_s + base;
    out[i].drift_ppm = rng.uniform(-c.drift_ppm, c.drift_ppm);
  }
  out[0].step_at_s = c.step_at_s;
  out[0].step_s = c.step_s;
  return out;
}

// UAV k's clock in draw_clocks()'s list.
std::size_t uav_clock(const MissionConfig& cfg, int k) {
  return k == 0 ? 0 : static_cast<std::size_t>(cfg.ugvs + k);
}

constexpr double kAirborne_m = 0.5;  // a UAV this high has taken off (separation counts)

// Each robot's port on the simulated network: UGV i's is i, UAV k's the k-th from the end.
constexpr std::size_t uav_port(std::size_t k) {
  return platform::LoopbackTransport::kParticipants - 1 - k;
}

// Where UAV k of `cfg.uavs` starts: one alone at cfg.uav_start; several spread evenly over the
// span of the UGVs' starts (each over its own part of the line), at uav_start's y and height.
Vec3 uav_start_of(const MissionConfig& cfg, int k) {
  if (cfg.uavs <= 1) return cfg.uav_start;
  double lo = ugv_start(cfg, 0).p.x(), hi = lo;
  for (int i = 1; i < cfg.ugvs; ++i) {
    lo = std::min(lo, ugv_start(cfg, i).p.x());
    hi = std::max(hi, ugv_start(cfg, i).p.x());
  }
  const double x = lo + (k + 0.5) / cfg.uavs * (hi - lo);
  return {x, cfg.uav_start.y(), cfg.uav_start.z()};
}

// A loop that stops when its robot's board dies (FaultConfig::uav_lost_at_s).
class Mortal final : public platform::Task {
 public:
  Mortal(platform::Task& inner, const bool& dead) : inner_(inner), dead_(dead) {}
  const char* name() const override { return inner_.name(); }
  Status init(TimePoint now) override { return inner_.init(now); }
  void step(TimePoint now) override {
    if (!dead_) inner_.step(now);
  }
  void on_overrun(Duration d) override { inner_.on_overrun(d); }

 private:
  platform::Task& inner_;
  const bool& dead_;
};

// FaultConfig::uav_lost_at_s: a UAV's board dies (its loops stop, its body and devices fall
// silent).
class UavLossWatch final : public platform::Task {
 public:
  UavLossWatch(sim::SimWorld& world, int uav, double at_s)
      : world_(world), uav_(uav), at_(TimePoint{} + seconds(at_s)) {}
  const char* name() const override { return "uav_loss"; }
  void step(TimePoint now) override {
    if (dead || now < at_) return;
    world_.silence_uav(uav_);
    dead = true;
  }
  bool dead = false;

 private:
  sim::SimWorld& world_;
  int uav_;
  TimePoint at_;
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

// The ground cells the UAV never saw (within the arena and the UAV's map's window at the end:
// on a site larger than the window, what it held), for the figure.
void add_unknown_cells(const uav::UavSupervisorTask& uav, const sim::BoxWorld& w,
                       MissionTrace& trace) {
  const auto& g = uav.mapper().geometry();
  const CellIndex lo = g.layer().cell_of(Vec2(w.min_x_m, w.min_y_m));
  const CellIndex hi = g.layer().cell_of(Vec2(w.max_x_m, w.max_y_m));
  for (int y = std::max(lo.y, 0); y <= std::min(hi.y, g.cells_y() - 1); ++y) {
    for (int x = std::max(lo.x, 0); x <= std::min(hi.x, g.cells_x() - 1); ++x) {
      if (uav.sharer().classify(uav.mapper(), x, y) == CellState::kUnknown) {
        trace.unknown_cells.push_back(g.layer().center_of({x, y}));
      }
    }
  }
}

// One UGV: its CAN drivers on the world's link, its task, the outbox its lane publishes through
// and the link its firmware process sees of it (the process may die and start again:
// FaultConfig::kill_ugv).
struct UgvStack {
  std::unique_ptr<platform::LaneOutbox> outbox;
  std::unique_ptr<RebootLink> link;
  std::unique_ptr<hal::can::CanBase> base;
  std::unique_ptr<ugv::UgvNavTask> task;
  std::unique_ptr<SelfPerceptionTask> perception;
  Vec2 goal;
  ugv::UgvNavConfig config;  // what a restarted process starts from
  // Its firmware's processes: the current one's number, whether it is dead, how long it has stood
  // still dead (a fault, s) and what the earlier ones waited (s per part).
  int generation = 0;
  bool dead = false;
  double stood_dead_s = 0.0;
  std::array<double, ugv::kWaitParts> earlier_waiting_s{};
  std::array<double, ugv::kSupportCauses> earlier_support_s{};
  // Waiting so far across its processes (s per part; the support part by cause).
  std::array<double, ugv::kWaitParts> waiting_parts_s() const {
    std::array<double, ugv::kWaitParts> out = plus(earlier_waiting_s, task->waiting_parts());
    out[static_cast<std::size_t>(ugv::WaitPart::kFault)] += stood_dead_s;
    return out;
  }
  std::array<double, ugv::kSupportCauses> support_causes_s() const {
    return plus(earlier_support_s, task->support_causes());
  }
  template <std::size_t N>
  static std::array<double, N> plus(std::array<double, N> earlier,
                                    const std::array<Duration, N>& now) {
    for (std::size_t k = 0; k < N; ++k)
      earlier[k] += to_seconds(now[k]);
    return earlier;
  }
  // Starts a firmware process: its CAN drivers on `can`, its task from `config` on the link.
  void start_firmware(hal::CanBus& can, const hal::can::BaseConfig& protocol,
                      const hal::can::WheelGeometry& wheels) {
    base = std::make_unique<hal::can::CanBase>(can, protocol, wheels);
    task = std::make_unique<ugv::UgvNavTask>(config, *link, base->odometry(), base->drive());
  }
  // What the earlier processes waited, and this one while dead (s).
  double waited_before_s() const {
    double sum = stood_dead_s;
    for (double w : earlier_waiting_s)
      sum += w;
    return sum;
  }
};

// One loop of a UGV's firmware across its processes: it steps the running process's loop,
// nothing while none runs, and initialises a new process's loop before its first step.
class UgvBoardRow final : public platform::Task {
 public:
  UgvBoardRow(UgvStack& ugv, std::size_t row, int lane) : ugv_(ugv), row_(row), lane_(lane) {}
  const char* name() const override { return current().name(); }
  Status init(TimePoint now) override {
    generation_ = ugv_.generation;
    return current().init(now);
  }
  void step(TimePoint now) override {
    if (ugv_.dead) return;
    if (generation_ != ugv_.generation) {
      generation_ = ugv_.generation;
      (void)current().init(now);  // its readers take the link's relays over: nothing to refuse
    }
    current().step(now);
  }
  void on_overrun(Duration d) override {
    if (!ugv_.dead) current().on_overrun(d);
  }

 private:
  platform::Task& current() const { return *ugv_.task->rows(lane_)[row_].task; }
  UgvStack& ugv_;
  std::size_t row_;
  int lane_;
  int generation_ = 0;
};

// FaultConfig::kill_ugv: the UGV's firmware process dies (its loops stop, its readers go, its
// base's watchdog stops the wheels) and, restart_after_s later, a new one starts from the same
// configuration, on a new CAN socket (nothing the base sent meanwhile reaches it).
class UgvKillWatch final : public platform::Task {
 public:
  UgvKillWatch(sim::SimWorld& world, UgvStack& ugv, int id, const FaultConfig& f)
      : world_(world),
        ugv_(ugv),
        id_(id),
        kill_at_s_(f.kill_ugv_at_s),
        restart_after_s_(f.restart_after_s) {}
  static constexpr Duration kPeriod = 20ms;
  const char* name() const override { return "ugv_kill"; }
  void step(TimePoint now) override {
    const double t = to_seconds(now);
    if (!killed_ && t >= kill_at_s_) {
      killed_ = true;
      ugv_.dead = true;
      ugv_.link->kill();
    }
    if (!ugv_.dead) return;
    if (restart_after_s_ >= 0.0 && t >= kill_at_s_ + restart_after_s_) {
      restart();
      return;
    }
    // Standing dead is waiting (a fault); coasting to a stop on the base's watchdog is not.
    if (std::abs(world_.ugv(id_).speed_mps()) < ugv::kStillSpeed_mps)
      ugv_.stood_dead_s += to_seconds(kPeriod);
  }

 private:
  void restart() {
    ugv_.earlier_waiting_s = ugv_.waiting_parts_s();
    ugv_.earlier_support_s = ugv_.support_causes_s();
    ugv_.stood_dead_s = 0.0;
    ugv_.task.reset();
    ugv_.base.reset();
    hal::CanFrame frame;
    hal::CanBus& can = world_.ugv_can(id_);
    while (can.receive(frame)) {
    }
    const sim::UgvBodyConfig& body = world_.ugv(id_).config();
    ugv_.link->start();
    ugv_.start_firmware(can, body.base, body.geometry);
    ++ugv_.generation;
    ugv_.dead = false;
  }
  sim::SimWorld& world_;
  UgvStack& ugv_;
  int id_;
  double kill_at_s_, restart_after_s_;
  bool killed_ = false;
};

// The ground truth of standing still, every world step: each UGV slower than 0.05 m/s before
// its firmware says it arrived (collided ones included: they stand).
class StillWatch final : public platform::Task {
 public:
  StillWatch(const sim::SimWorld& world, const std::vector<UgvStack>& ugvs)
      : counts(ugvs.size()), world_(world), ugvs_(ugvs) {}
  const char* name() const override { return "still_watch"; }
  void step(TimePoint) override {
    for (std::size_t i = 0; i < ugvs_.size(); ++i) {
      counts[i].update(ugvs_[i].task->mode() == msg::UgvMode::kArrived,
                       world_.ugv(static_cast<int>(i)).speed_mps(), 0.02);
    }
  }
  std::vector<StillCount> counts;

 private:
  const sim::SimWorld& world_;
  const std::vector<UgvStack>& ugvs_;
};

// FaultConfig::base_fault_at_s: UGV 0's base faults; how long until its firmware says so and
// its wheels stand, and whether they move again.
class BaseFaultWatch final : public platform::Task {
 public:
  BaseFaultWatch(sim::SimWorld& world, const UgvStack& ugv, double at_s)
      : world_(world), ugv_(ugv), at_(TimePoint{} + seconds(at_s)) {}
  const char* name() const override { return "base_fault"; }
  void step(TimePoint now) override {
    if (now < at_) return;
    if (!out.injected) {
      world_.set_base_fault(0, true);
      out.injected = true;
    }
    const double since = to_seconds(now - at_);
    if (out.firmware_fault_after_s < 0.0 && ugv_.task->mode() == msg::UgvMode::kFault)
      out.firmware_fault_after_s = since;
    const double speed = world_.ugv(0).speed_mps();
    if (out.still_after_s >= 0.0) {
      out.max_speed_after_still = std::max(out.max_speed_after_still, std::abs(speed));
    } else if (std::abs(speed) < 0.01) {
      out.still_after_s = since;
    }
  }
  BaseFaultOutcome out;

 private:
  sim::SimWorld& world_;
  const UgvStack& ugv_;
  TimePoint at_;
};

}  // namespace

// Everything a mission owns, in construction order (destroyed in reverse).
struct Mission::Parts {
  std::vector<std::string> warnings;  // about the map
  MissionConfig cfg;
  std::chrono::steady_clock::time_point wall_start;
  platform::MonotonicClock stopwatch;
  std::unique_ptr<platform::LockstepExecutor> ex;
  std::unique_ptr<platform::LoopbackTransport> bus;
  std::unique_ptr<platform::WorkerPool> pool;
  std::unique_ptr<sim::SimWorld> world;
  std::unique_ptr<WorldTask> world_task;
  std::unique_ptr<StillWatch> still;
  std::unique_ptr<BaseFaultWatch> base_fault;
  std::unique_ptr<platform::TransportPump> pump;
  std::vector<std::unique_ptr<uav::UavSupervisorTask>> uavs;
  std::unique_ptr<UavLossWatch> uav_loss;
  std::unique_ptr<UgvKillWatch> ugv_kill;
  std::vector<std::unique_ptr<UgvBoardRow>> board_rows;
  std::vector<std::unique_ptr<Mortal>> mortals;
  std::unique_ptr<ReferenceFrameTask> reference;
  std::vector<UgvStack> ugvs;
  std::vector<sim::ClockModel> clocks;  // the UAV's, then each UGV's
  std::vector<std::unique_ptr<OnRobotClock>> on_clocks;
  FlushOutboxes flush;
  std::unique_ptr<SupportLog> support;
  // What fly() found, for collect().
  std::vector<UgvOutcome> outcomes;
  double uav_min_separation_m = -1.0;
};

Mission::Mission(std::unique_ptr<Parts> parts) : parts_(std::move(parts)) {}
Mission::~Mission() = default;

const platform::LockstepExecutor& Mission::executor() const {
  return *parts_->ex;
}
const MissionConfig& Mission::config() const {
  return parts_->cfg;
}
const sim::SimWorld& Mission::world() const {
  return *parts_->world;
}
const uav::UavSupervisorTask* Mission::uav(std::size_t k) const {
  return k < parts_->uavs.size() ? parts_->uavs[k].get() : nullptr;
}
std::size_t Mission::uav_count() const {
  return parts_->uavs.size();
}
std::size_t Mission::ugv_count() const {
  return parts_->ugvs.size();
}
const ugv::UgvNavTask& Mission::ugv(std::size_t i) const {
  return *parts_->ugvs.at(i).task;
}

std::unique_ptr<Mission> Mission::compose(const MissionConfig& cfg, std::string& error) {
  if (!check(cfg, error)) return nullptr;
  sim::BoxWorld boxes;
  std::vector<std::string> warnings;
  if (!build_world(cfg, boxes, error, &warnings)) return nullptr;
  if (cfg.warn) {
    for (const std::string& w : warnings)
      cfg.warn(w);
  }

  auto p = std::make_unique<Parts>();
  p->cfg = cfg;
  p->warnings = warnings;
  p->wall_start = std::chrono::steady_clock::now();
  p->ex = std::make_unique<platform::LockstepExecutor>(TimePoint{}, &p->stopwatch);
  p->bus = std::make_unique<platform::LoopbackTransport>(cfg.seed);
  p->clocks = draw_clocks(cfg);
  const sim::SimWorldConfig wc = sim_world_config(cfg);
  const std::vector<sim::WheelErrors> wheels = draw_wheels(cfg);
  p->pool = std::make_unique<platform::WorkerPool>(cfg.threads - 1);
  p->world = std::make_unique<sim::SimWorld>(wc, boxes, p->ex->clock(), p->pool.get());
  p->world_task = std::make_unique<WorldTask>(*p->world);
  p->pump = std::make_unique<platform::TransportPump>(*p->bus);
  // The network (one for every robot) and the world come first in the table.
  Status st = p->ex->add({p->pump.get(), 10ms, 2ms});
  if (st) st = p->ex->add({p->world_task.get(), 20ms, 20ms});

  // The UAVs (not in the self-perception baseline).
  if (!cfg.self_perception) {
    for (int k = 0; k < cfg.uavs; ++k) {
      p->world->add_uav(uav_start_of(cfg, k), p->clocks[uav_clock(cfg, k)]);
      uav::UavSupervisorConfig uc;
      uc.id = static_cast<RobotId>(k);
      if (cfg.ablation == Ablation::kNoScheduling)
        uc.scheduler.mode = uav::ScheduleMode::kNoScheduling;
      if (cfg.ablation == Ablation::kNoTimeWindows)
        uc.scheduler.mode = uav::ScheduleMode::kNoTimeWindows;
      uc.scouting = cfg.scouting;
      uc.lidar_pattern = beam_pattern_of(wc.lidar);
      uc.camera_view = camera_view_of(wc.camera);
      sim::SimWorld& w = *p->world;
      p->uavs.push_back(std::make_unique<uav::UavSupervisorTask>(
          uc, p->bus->port(uav_port(static_cast<std::size_t>(k))), w.uav(k), w.uav_lidar(k),
          w.uav_camera(k), w.uav(k), p->pool.get()));
    }
  } else {
    p->reference = std::make_unique<ReferenceFrameTask>(p->bus->port(uav_port(0)));
  }

  // The UGVs, each behind its own CAN link, each publishing through its own outbox: a UGV's
  // tasks are a lane of the executor, the UGVs' lanes run side by side on the worker pool.
  p->ugvs.resize(static_cast<std::size_t>(cfg.ugvs));
  for (int i = 0; i < cfg.ugvs; ++i) {
    p->world->add_ugv(ugv_start(cfg, i), p->clocks[static_cast<std::size_t>(i) + 1],
                      &wheels[static_cast<std::size_t>(i)]);
  }
  if (cfg.self_perception) p->world->enable_ugv_lidars();
  // Goals and start guesses are given where the UAV's map has them: in its odometry's frame
  // (the world's own in the ideal world and without a UAV).
  const sim::OdometryFrame& map_frame = p->world->odometry_frame();
  for (int i = 0; i < cfg.ugvs; ++i) {
    UgvStack& s = p->ugvs[static_cast<std::size_t>(i)];
    s.goal = ugv_goal(cfg, i);
    ugv::UgvNavConfig nc;
    nc.id = static_cast<RobotId>(i);
    nc.goal = map_frame.to_odometry(s.goal);
    for (const Vec2& v : ugv_via(cfg, i))
      (void)nc.via.push_back(map_frame.to_odometry(v));  // check() bounds their number
    nc.has_start_guess = true;
    nc.start_guess = map_frame.to_odometry(ugv_start(cfg, i));
    nc.use_rpe_updates = cfg.ablation != Ablation::kNoRpe;
    nc.predictor.use_uncertainty = cfg.ablation != Ablation::kNoUncertainty;
    nc.predictor.horizon_m = cfg.predict_horizon_m;
    nc.map.unknown_blocks_prediction = !cfg.self_perception;
    s.outbox = std::make_unique<platform::LaneOutbox>(p->bus->port(static_cast<std::size_t>(i)));
    s.link = std::make_unique<RebootLink>(*s.outbox);
    s.config = nc;
    s.start_firmware(p->world->ugv_can(i), wc.ugv.base, wc.ugv.geometry);
    if (cfg.self_perception)
      s.perception =
          std::make_unique<SelfPerceptionTask>(*s.outbox, *p->world, i, beam_pattern_of(wc.lidar));
  }
  for (const UgvStack& s : p->ugvs)
    p->flush.outboxes.push_back(s.outbox.get());
  p->ex->set_lanes(p->pool.get(), &p->flush);

  // The robots' loops, each from its own schedule table: the UAVs' in one lane, then each
  // UGV's in its own lane. The UGVs plan at the same instants (each has its own computer: nothing
  // keeps their loops apart, and the firmware must be safe when they line up), so the lanes plan
  // side by side. Each on its robot's clock (the self-perception baseline's stand-ins: the UAV's).
  const auto on_clock = [&p](platform::TaskEntry e, const sim::ClockModel& clock) {
    if (clock.identity()) return e;
    p->on_clocks.push_back(std::make_unique<OnRobotClock>(*e.task, clock));
    e.task = p->on_clocks.back().get();
    return e;
  };
  const auto add_rows = [&](auto rows, const sim::ClockModel& clock) {
    Status added = Status::ok();
    for (const platform::TaskEntry& e : rows)
      if (added) added = p->ex->add(on_clock(e, clock));
    return added;
  };
  p->still = std::make_unique<StillWatch>(*p->world, p->ugvs);
  if (st) st = p->ex->add({p->still.get(), 20ms, 1ms});
  if (cfg.faults.base_fault_at_s >= 0.0) {
    p->base_fault =
        std::make_unique<BaseFaultWatch>(*p->world, p->ugvs.front(), cfg.faults.base_fault_at_s);
    if (st) st = p->ex->add({p->base_fault.get(), 20ms, 1ms});
  }
  const int lost = cfg.faults.uav_lost_id >= 0 ? cfg.faults.uav_lost_id : cfg.uavs - 1;
  if (cfg.faults.uav_lost_at_s >= 0.0 && !p->uavs.empty()) {
    p->uav_loss = std::make_unique<UavLossWatch>(*p->world, lost, cfg.faults.uav_lost_at_s);
    if (st) st = p->ex->add({p->uav_loss.get(), 20ms, 1ms});
  }
  if (cfg.faults.kill_ugv >= 0 && cfg.faults.kill_ugv < cfg.ugvs) {
    p->ugv_kill = std::make_unique<UgvKillWatch>(
        *p->world, p->ugvs[static_cast<std::size_t>(cfg.faults.kill_ugv)], cfg.faults.kill_ugv,
        cfg.faults);
    if (st) st = p->ex->add({p->ugv_kill.get(), UgvKillWatch::kPeriod, 1ms});
  }
  if (p->reference && st) st = p->ex->add(on_clock({p->reference.get(), 20ms, 1ms}, p->clocks[0]));
  // The UAVs share lane 1 (one after the other: they publish straight onto the bus, which no
  // other lane touches until the barrier), so that a UAV's scan insertion runs beside the UGVs'
  // planning rather than before it.
  constexpr int kUavLane = 1;
  for (std::size_t k = 0; k < p->uavs.size() && st; ++k) {
    auto rows = p->uavs[k]->rows(kUavLane);
    if (p->uav_loss && static_cast<int>(k) == lost) {
      for (platform::TaskEntry& e : rows) {  // the one that will die
        p->mortals.push_back(std::make_unique<Mortal>(*e.task, p->uav_loss->dead));
        e.task = p->mortals.back().get();
      }
    }
    st = add_rows(rows, p->clocks[uav_clock(cfg, static_cast<int>(k))]);
  }
  for (int i = 0; i < cfg.ugvs && st; ++i) {
    UgvStack& s = p->ugvs[static_cast<std::size_t>(i)];
    const int lane = kUavLane + 1 + i;
    std::array<platform::TaskEntry, 2> rows = s.task->rows(lane);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      p->board_rows.push_back(std::make_unique<UgvBoardRow>(s, k, lane));
      rows[k].task = p->board_rows.back().get();
    }
    st = add_rows(rows, p->clocks[static_cast<std::size_t>(i) + 1]);
    if (st && s.perception)
      st = p->ex->add(on_clock({s.perception.get(), 50ms, 10ms, Duration{}, lane}, p->clocks[0]));
  }
  p->support = std::make_unique<SupportLog>(cfg.ugvs);
  if (st) st = p->bus->subscribe(msg::topic_of<msg::CollisionInfo>, kAnyRobot, *p->support);
  if (st) st = p->ex->init();
  if (!st) {
    error = std::string("cannot build the mission: ") + st.message();
    return nullptr;
  }
  return std::unique_ptr<Mission>(new Mission(std::move(p)));
}

void Mission::fly(MissionTrace* trace, MissionWatcher* watcher) {
  Parts& p = *parts_;
  const MissionConfig& cfg = p.cfg;
  const std::vector<UgvStack>& ugvs = p.ugvs;
  p.support->trace = trace;
  if (trace != nullptr) {
    *trace = MissionTrace{};
    trace->world = p.world->world();
    trace->ugv_paths.resize(ugvs.size());
    trace->ugv_ellipses.resize(ugvs.size());
    for (const auto& s : ugvs)
      trace->goals.push_back(s.goal);
    for (int i = 0; i < cfg.ugvs; ++i)
      trace->vias.push_back(ugv_via(cfg, i));
  }

  // Run, watching the truth every 100 ms.
  p.outcomes.assign(ugvs.size(), UgvOutcome{});
  for (std::size_t i = 0; i < ugvs.size(); ++i) {
    // What the wheels' errors make of the estimator's calibration: with each encoder reporting
    // (1 + s) x its wheel, the body's v = (u_l m_l + u_r m_r) / 2 and w = (u_r m_r - u_l m_l) / L
    // with u = 1 / (1 + s): scale and turn scale (u_l + u_r) / 2 - 1, drift per metre
    // (u_r - u_l) / L; the slip is the world's (it acts on the true turn rate, near enough).
    const sim::UgvBodyConfig& bc = p.world->ugv(static_cast<int>(i)).config();
    const sim::WheelErrors& e = bc.wheel_errors;
    const double ul = 1.0 / ((1.0 + e.left_scale) * (1.0 + bc.encoder_bias));
    const double ur = 1.0 / ((1.0 + e.right_scale) * (1.0 + bc.encoder_bias));
    p.outcomes[i].calibration_true = {0.5 * (ul + ur) - 1.0, 0.5 * (ul + ur) - 1.0,
                                      (ur - ul) / bc.geometry.track_width_m, e.yaw_rate_bias_radps,
                                      e.slip_per_radps};
  }
  const TimePoint end = time_at_seconds(cfg.max_time_s);
  int tick = 0;
  std::vector<int> open_stops(ugvs.size(), -1);  // index of each UGV's current stop in the trace
  while (p.ex->now() < end) {
    apply_faults(cfg.faults, to_seconds(p.ex->now()), *p.bus);
    p.ex->run_until(p.ex->now() + 100ms);
    ++tick;
    if (watcher != nullptr) watcher->watch(*this);
    const double t = to_seconds(p.ex->now());
    bool all_done = true;
    for (std::size_t i = 0; i < ugvs.size(); ++i) {
      const ugv::UgvNavTask& task = *ugvs[i].task;
      UgvOutcome& o = p.outcomes[i];
      const sim::UgvBody& body = p.world->ugv(static_cast<int>(i));
      // Waiting as a user sees it: standing still (by the true motion) before it reached.
      const Pose2 now_pose = body.pose();
      o.stopped_s = p.still->counts[i].stopped_s;
      o.stops = p.still->counts[i].stops;
      // How honest its covariance is: NEES of (x, y, yaw) against the truth.
      const UgvEkf& ekf = task.estimator();
      // Its estimate is in the UAV odometry's frame: so is the truth it is held against. A dead
      // firmware process has no estimate.
      const bool running = !ugvs[i].dead;
      if (running && ekf.initialized() && task.mode() != msg::UgvMode::kArrived && !body.frozen()) {
        const Pose2 truth = p.world->odometry_frame().to_odometry(now_pose);
        add_to_mean(pose_nees(ekf.pose(), ekf.covariance(), truth), o.nees_mean, o.nees_samples);
        for (std::size_t k = 0; k < o.calibration.size(); ++k) {
          const int s = kPoseDim + static_cast<int>(k);
          o.calibration[k] = ekf.state()(s);
          o.calibration_sigma[k] = std::sqrt(ekf.state_covariance()(s, s));
        }
      }
      // A dead firmware process stands as a fault would.
      const msg::UgvMode mode = running ? task.mode() : msg::UgvMode::kFault;
      o.final_mode = mode;
      o.clock_steps = task.fleet_clock().filter().counters().steps;
      o.clock_error_s = task.fleet_clock().error_s(task.now());
      const std::array<double, ugv::kWaitParts> parts = ugvs[i].waiting_parts_s();
      o.waiting_time_s = task.waiting_time_s() + ugvs[i].waited_before_s();
      for (std::size_t k = 0; k < ugv::kWaitParts; ++k)
        o.waiting_parts[k] = parts[k];
      o.support_causes = ugvs[i].support_causes_s();
      if (mode == msg::UgvMode::kBlocked) {
        o.blocked_s += 0.1;
        o.blocked_reason = task.blocked_reason();
      }
      if (trace != nullptr) {
        const bool stopped = mode != msg::UgvMode::kDriving && mode != msg::UgvMode::kArrived;
        auto& open = open_stops[i];
        if (stopped && open >= 0) {
          const MissionTrace::Stop& s = trace->stops[static_cast<std::size_t>(open)];
          if (s.why != mode || s.blocked != task.blocked_reason()) open = -1;  // a new why
        }
        if (stopped && open < 0) {
          open = static_cast<int>(trace->stops.size());
          trace->stops.push_back(
              {static_cast<int>(i), t - 0.1, t, body.pose().p, mode, task.blocked_reason()});
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
      const bool dead_for_good = !running && cfg.faults.restart_after_s < 0.0;
      all_done = all_done && (arrived || body.frozen() || dead_for_good);
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
    for (std::size_t a = 0; a < p.uavs.size(); ++a) {
      for (std::size_t b = a + 1; b < p.uavs.size(); ++b) {
        const Vec3 pa = p.world->uav(static_cast<int>(a)).state().pose.p;
        const Vec3 pb = p.world->uav(static_cast<int>(b)).state().pose.p;
        if (pa.z() < kAirborne_m || pb.z() < kAirborne_m) continue;
        const double d = (pa - pb).norm();
        if (p.uav_min_separation_m < 0.0 || d < p.uav_min_separation_m) p.uav_min_separation_m = d;
      }
    }
    if (trace != nullptr && tick % 5 == 0) {
      trace->uav_paths.resize(p.uavs.size());
      for (std::size_t k = 0; k < p.uavs.size(); ++k)
        trace->uav_paths[k].push_back(p.world->uav(static_cast<int>(k)).state().pose.p.head<2>());
    }
    if (cfg.progress && tick % 10 == 0) cfg.progress(t / cfg.max_time_s);
    if (all_done) break;
  }
}

MissionOutcome Mission::collect(MissionTrace* trace) const {
  const Parts& p = *parts_;
  MissionOutcome out;
  out.config = p.cfg;
  out.config.progress = nullptr;
  out.config.warn = nullptr;
  out.warnings = p.warnings;
  out.ugvs = p.outcomes;
  if (p.base_fault) out.base_fault = p.base_fault->out;
  out.ugvs.resize(p.ugvs.size());
  const platform::Schedule& table = p.ex->schedule();
  for (std::size_t i = 0; i < table.size(); ++i) {
    const platform::TaskStats& stats = table.stats(i);
    auto it = std::find_if(out.task_times.begin(), out.task_times.end(),
                           [&](const TaskTime& t) { return t.name == stats.name; });
    if (it == out.task_times.end()) it = out.task_times.insert(it, TaskTime{stats.name});
    it->steps += stats.steps;
    it->total_s += to_seconds(stats.total_step);
    it->longest_ms = std::max(it->longest_ms, to_seconds(stats.longest_step) * 1e3);
  }
  out.sim_time_s = to_seconds(p.ex->now());
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - p.wall_start).count();
  for (std::size_t i = 0; i < p.ugvs.size(); ++i) {
    UgvOutcome& o = out.ugvs[i];
    o.id = static_cast<int>(i);
    o.support_requests = p.support->requests[i];
    if (out.sim_time_s > 0.0) {
      const platform::ParticipantTraffic& t = p.bus->traffic(i);
      o.bytes_in_per_s = static_cast<double>(t.bytes_in) / out.sim_time_s;
      for (std::size_t k = 0; k < msg::kTopicCount; ++k)
        o.bytes_in_by_topic_per_s[k] = static_cast<double>(t.bytes_in_by_topic[k]) / out.sim_time_s;
    }
    if (!o.reached) o.reach_time_s = -1.0;
  }
  summarise(*p.world, out);
  if (out.sim_time_s > 0.0) {  // per UAV (the first's)
    out.uav_bytes_in_per_s =
        static_cast<double>(p.bus->traffic(uav_port(0)).bytes_in) / out.sim_time_s;
    out.uav_bytes_out_per_s =
        static_cast<double>(p.bus->traffic(uav_port(0)).bytes_out) / out.sim_time_s;
  }
  out.uav_min_separation_m = p.uav_min_separation_m;
  // With several UAVs: their sums (their time in each mode, their flying, their patches, ...).
  for (std::size_t k = 0; k < p.uavs.size(); ++k) {
    const uav::UavSupervisorTask& u = *p.uavs[k];
    out.uav_traj_length_m += p.world->uav(static_cast<int>(k)).travelled_m();
    out.map_patches += u.sharer().counters().patches;
    out.map_patch_bytes += u.sharer().counters().bytes;
    out.schedules += u.health().schedules;
    out.schedules_exact += u.health().schedules_exact;
    out.plan_age_max = std::max(out.plan_age_max, u.health().plan_age_max);
    const auto mode_s = [&](uav::UavMode m) {
      return static_cast<double>(u.health().mode_steps[static_cast<std::size_t>(m)]) *
             to_seconds(u.config().schedule.scheduling.period);
    };
    out.uav_idle_s += mode_s(uav::UavMode::kIdle);
    out.uav_transit_s += mode_s(uav::UavMode::kTransit);
    out.uav_hover_s += mode_s(uav::UavMode::kHover);
    out.uav_scout_s += mode_s(uav::UavMode::kScout);
    out.scout_timeouts += u.health().scout_timeouts;
    out.team_located += u.team_filter().counters().located;
    out.team_returns_dropped += u.team_filter().counters().dropped;
  }
  if (trace != nullptr) {
    for (const auto& c : p.world->collisions())
      trace->collisions.push_back(c.where);
    if (!p.uavs.empty()) add_unknown_cells(*p.uavs.front(), p.world->world(), *trace);
  }
  return out;
}

Result<MissionOutcome> run_mission(const MissionConfig& cfg, MissionTrace* trace,
                                   std::string* error_out, MissionWatcher* watcher) {
  std::string error;
  const std::unique_ptr<Mission> mission = Mission::compose(cfg, error);
  if (!mission) {
    if (error_out != nullptr) *error_out = error;
    return Status{Errc::kInvalidArgument, "mission configuration"};
  }
  mission->fly(trace, watcher);
  return mission->collect(trace);
}

}  // namespace colag::mission
