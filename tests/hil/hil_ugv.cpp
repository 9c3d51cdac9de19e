// The UGV board's CAN stack in the loop (scripts/hil): the real SocketCAN driver, the base's
// driver of --protocol (colag, odrive or agilex_v2: wheel odometry and drive) under the real-time
// executor at 50 Hz, against colag_motor_emulator speaking the same protocol on the interface. It
// drives a profile (straight, turn, stop), integrates the encoder odometry, and keeps the board's
// watchdog: encoder frames stale for > 60 ms => command zero speed and report the fault. Exits 0
// only if everything checked holds. Robust to a slow (starved) VM: the profile starts at the
// emulator's first encoder frame, the run lasts until the watchdog has tripped (at most --seconds),
// and the odometry is judged against the wheels' true travel the emulator reports
// (--emulator-report), whatever commands reached it and when. No encoder frame at all within
// --seconds is a precondition not met: exit code 77 (a skip), with the reason.
//
//   colag_hil_ugv run [--interface vcan0] [--seconds 20] [--emulator-report FILE]
//                     [--protocol colag|odrive|agilex_v2]
//   colag_hil_ugv check-log FILE [--min-commands N]   (a `candump -L` log of the run)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include "colag/hal/can/can_base.hpp"
#include "colag/hal/linux/socketcan_bus.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/hal/sim/can_link.hpp"
#include "colag/platform/realtime_executor.hpp"
#include "colag/sim/world/ugv_body.hpp"

namespace {
using namespace colag;

// 2 s straight at 0.3 m/s, 1 s turning at 0.5 rad/s while rolling at 0.2 m/s, then stop.
hal::DriveCommand profile(double t) {
  if (t < 2.0) return {TimePoint{}, 0.3, 0.0};
  if (t < 3.0) return {TimePoint{}, 0.2, 0.5};
  return {TimePoint{}, 0.0, 0.0};
}

class CanStackTask final : public platform::Task {
 public:
  CanStackTask(hal::CanBus& bus, const hal::can::BaseConfig& base)
      : base_(bus, base, {}), odometry_(base_.odometry()), drive_(base_.drive()) {}
  const char* name() const override { return "ugv_can"; }
  void step(TimePoint now) override {
    hal::WheelOdometrySample s;
    while (odometry_.poll(s)) {
      if (!started_) {  // the emulator is up: the profile starts now
        started_ = true;
        start_ = now;
      }
      const double dt = last_.time_since_epoch().count() == 0 ? 0.0 : to_seconds(s.stamp - last_);
      last_ = s.stamp;
      yaw_ += s.omega_radps * dt;
      x_ += s.v_mps * dt * std::cos(yaw_);
      y_ += s.v_mps * dt * std::sin(yaw_);
      distance_ += std::abs(s.v_mps) * dt;
      ++samples_;
    }
    const TimePoint heard = odometry_.last_sample_time();
    const bool stale = heard != TimePoint{} && now - heard > std::chrono::milliseconds(60);
    if (stale && !tripped_) {
      tripped_ = true;
      trip_delay_ = now - heard;
      tripped_at_ = now;
    }
    if (tripped_) {
      (void)drive_.stop(now);  // the watchdog: zero speed until odometry is back
      return;
    }
    hal::DriveCommand c = started_ ? profile(to_seconds(now - start_)) : hal::DriveCommand{};
    c.stamp = now;
    if (!drive_.command(c)) ++send_failures_;
  }
  void shutdown(TimePoint now) { drive_.shutdown(now); }

  double x_ = 0, y_ = 0, yaw_ = 0, distance_ = 0;
  std::uint64_t samples_ = 0, send_failures_ = 0;
  bool started_ = false;  // an encoder frame came: the emulator is running
  bool tripped_ = false;
  Duration trip_delay_{};
  TimePoint tripped_at_{};
  hal::can::CanBase base_;
  hal::WheelOdometry& odometry_;
  hal::Drive& drive_;

 private:
  TimePoint start_{}, last_{};
};

// What the same profile gives on the simulator's noise-free wheel model (same controller code,
// same drive driver, in memory): the reference the real-time run is compared with.
struct Reference {
  double distance_m, yaw_rad;
};
Reference reference(const hal::can::BaseConfig& base) {
  hal::scripted::ManualClock clock;
  hal::sim::SimCanLink link(clock);
  hal::can::CanBase driver(link.board(), base, {});
  hal::Drive& drive = driver.drive();
  sim::UgvBodyConfig cfg;
  cfg.base = base;
  cfg.motion_noise_fraction = 0.0;
  cfg.odometry_noise = {};
  sim::UgvBody body(cfg, Pose2{}, 1);
  hal::CanFrame f;
  for (int k = 0; k < 250; ++k) {  // 5 s at 50 Hz
    hal::DriveCommand c = profile(k * 0.02);
    c.stamp = clock.now();
    (void)drive.command(c);
    body.step(clock.now(), 0.02, link.motor());
    while (link.board().receive(f)) {
    }
    clock.advance(std::chrono::milliseconds(20));
  }
  return {body.travelled_m(), body.pose().yaw_rad};
}

// The wheels' true travel, as colag_motor_emulator --report writes it when it stops.
bool read_report(const std::string& path, double max_wait_s, Reference& out) {
  for (double waited = 0.0; waited <= max_wait_s; waited += 0.1) {
    std::ifstream in(path);
    if (in >> out.distance_m >> out.yaw_rad) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

int run(const std::string& interface, double max_s, const std::string& emulator_report,
        const hal::can::BaseConfig& base) {
  platform::RealtimeExecutor exec;
  linux_hal::SocketCanConfig cfg;
  cfg.interface = interface;
  for (const hal::can::IdFilter& f : hal::can::base_filters(base))
    (void)cfg.filters.push_back({f.id, f.mask, f.extended});
  linux_hal::SocketCanBus bus(cfg, exec.clock());
  if (const Status s = bus.open(); !s) {
    std::fprintf(stderr, "hil_ugv: %s\n", s.message());
    return 1;
  }
  CanStackTask task(bus, base);
  (void)exec.add({&task, std::chrono::milliseconds(20), std::chrono::milliseconds(10), {}});
  const platform::RealtimeSetup setup = exec.apply({.fifo_priority = 50, .lock_memory = true});
  if (!exec.init()) return 1;
  // Until the watchdog has tripped (the emulator stopped) and 0.3 s more, or the time is up.
  const TimePoint end = exec.clock().now() + seconds(max_s);
  while (exec.clock().now() < end &&
         !(task.tripped_ && exec.clock().now() - task.tripped_at_ > std::chrono::milliseconds(300)))
    exec.run_until(exec.clock().now() + std::chrono::milliseconds(100));
  task.shutdown(exec.clock().now());
  if (!task.started_) {
    std::printf(
        "hil_ugv: SKIP: no encoder frame from the motor emulator in %.0f s (the VM too "
        "slow to start it?): nothing to judge\n",
        max_s);
    return 77;
  }

  // The reference: the wheels' true travel, from the emulator when it reports it (whatever
  // commands it got, and when), else what the profile gives on the noise-free wheel model.
  Reference ref = reference(base);
  const char* ref_name = "the simulated wheel model";
  if (!emulator_report.empty()) {
    if (!read_report(emulator_report, 5.0, ref)) {
      std::printf("hil_ugv: FAILED: no report from the motor emulator in %s\n",
                  emulator_report.c_str());
      return 1;
    }
    ref_name = "the emulator's wheels";
  }
  const hal::can::BaseCounters c = task.base_.counters();
  const double trip_ms = to_seconds(task.trip_delay_) * 1e3;
  std::printf("hil_ugv: SCHED_FIFO %s, mlockall %s\n", setup.fifo ? "yes" : "no",
              setup.memory_lock ? "yes" : "no");
  std::printf("hil_ugv: %llu odometry samples, distance %.3f m, pose x %.3f y %.3f yaw %.3f\n",
              static_cast<unsigned long long>(task.samples_), task.distance_, task.x_, task.y_,
              task.yaw_);
  std::printf(
      "hil_ugv: %s: frames %llu, lost %llu, bad %llu, implausible %llu, send failures %llu\n",
      hal::can::to_string(base.protocol), static_cast<unsigned long long>(c.frames),
      static_cast<unsigned long long>(c.lost), static_cast<unsigned long long>(c.bad_frames),
      static_cast<unsigned long long>(c.implausible),
      static_cast<unsigned long long>(task.send_failures_));
  std::printf("hil_ugv: watchdog %s%s%.0f ms after the last encoder frame\n",
              task.tripped_ ? "tripped " : "did not trip", task.tripped_ ? "" : " ", trip_ms);
  bool ok = true;
  const auto expect = [&](bool cond, const char* what) {
    if (!cond) std::printf("hil_ugv: FAILED: %s\n", what);
    ok = ok && cond;
  };
  std::printf("hil_ugv: reference (%s): distance %.3f m, yaw %.3f\n", ref_name, ref.distance_m,
              ref.yaw_rad);
  // The profile moves the wheels ~0.8 m: less means the commands did not get through.
  expect(ref.distance_m > 0.5, "the commands moved the wheels (> 0.5 m)");
  expect(std::abs(task.distance_ - ref.distance_m) < 0.05 * ref.distance_m + 0.02,
         "odometry distance within 5 % + 2 cm of the reference");
  expect(std::abs(task.yaw_ - ref.yaw_rad) < 0.05, "odometry heading within 0.05 rad");
  expect(c.bad_frames == 0, "no malformed frames");
  expect(task.samples_ > 150, "encoder samples at ~50 Hz");
  expect(task.tripped_ && trip_ms <= 100.0, "watchdog trips within 100 ms of the last frame");
  return ok ? 0 : 1;
}

// `candump -L` lines: "(1700000000.123456) vcan0 201#0102030405060708".
int check_log(const std::string& path, int min_commands) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "hil_ugv: cannot read %s\n", path.c_str());
    return 1;
  }
  const hal::can::WheelProtocolConfig protocol;
  std::map<std::uint32_t, int> frames;
  int bad = 0, gaps = 0;
  std::map<std::uint32_t, int> last_alive;
  hal::can::SpeedCommand last_command;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string stamp, iface, body;
    if (!(ls >> stamp >> iface >> body)) continue;
    const auto hash = body.find('#');
    if (hash == std::string::npos) continue;
    hal::CanFrame f;
    f.id = static_cast<std::uint32_t>(std::stoul(body.substr(0, hash), nullptr, 16));
    const std::string hex = body.substr(hash + 1);
    f.dlc = static_cast<std::uint8_t>(std::min<std::size_t>(hex.size() / 2, 8));
    for (int i = 0; i < f.dlc; ++i)
      f.data[i] = static_cast<std::uint8_t>(
          std::stoul(hex.substr(2 * static_cast<std::size_t>(i), 2), nullptr, 16));
    hal::can::DecodedFrame d;
    if (hal::can::decode(f, protocol, d) != hal::can::DecodeError::kNone) {
      ++bad;
      continue;
    }
    ++frames[f.id];
    const int alive = f.data[6];
    if (last_alive.count(f.id) != 0 && alive != ((last_alive[f.id] + 1) & 0xFF)) ++gaps;
    last_alive[f.id] = alive;
    if (d.kind == hal::can::FrameKind::kCommand) last_command = d.command;
  }
  std::printf(
      "hil_ugv: log %s: %d ENCODER_COUNTS, %d WHEEL_SPEEDS, %d SPEED_COMMAND, %d bad, "
      "%d alive gaps; last command %d/%d mm/s\n",
      path.c_str(), frames[0x101], frames[0x102], frames[0x201], bad, gaps, last_command.left_mmps,
      last_command.right_mmps);
  const bool ok = frames[0x101] > 100 && frames[0x102] > 100 && frames[0x201] >= min_commands &&
                  bad == 0 && gaps == 0 && last_command.left_mmps == 0 &&
                  last_command.right_mmps == 0;
  if (!ok) std::printf("hil_ugv: FAILED: the bus log is incomplete or malformed\n");
  return ok ? 0 : 1;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "check-log" && argc == 3) return check_log(argv[2], 150);
  if (mode == "check-log" && argc == 5 && std::strcmp(argv[3], "--min-commands") == 0)
    return check_log(argv[2], std::atoi(argv[4]));
  if (mode == "run") {
    std::string interface = "vcan0", report;
    double max_s = 20.0;
    hal::can::BaseConfig base;
    for (int i = 2; i + 1 < argc; i += 2) {
      if (std::strcmp(argv[i], "--interface") == 0) interface = argv[i + 1];
      if (std::strcmp(argv[i], "--seconds") == 0) max_s = std::atof(argv[i + 1]);
      if (std::strcmp(argv[i], "--emulator-report") == 0) report = argv[i + 1];
      if (std::strcmp(argv[i], "--protocol") == 0 &&
          !hal::can::parse_base_protocol(argv[i + 1], base.protocol)) {
        std::fprintf(stderr, "hil_ugv: --protocol: one of %s\n", hal::can::kBaseProtocolNames);
        return 2;
      }
    }
    return run(interface, max_s, report, base);
  }
  std::fprintf(stderr,
               "usage: %s run [--interface vcan0] [--seconds 20] [--emulator-report FILE] "
               "[--protocol colag|odrive|agilex_v2] | check-log FILE [--min-commands N]\n",
               argv[0]);
  return 2;
}
