// colag_smoke: the foundation's end-to-end check. One UAV task and one UGV task (stubs until
// their issues land) exchange messages over the loopback transport under the lock-step
// executor for 10 simulated seconds; prints the executor table and traffic, exits non-zero if
// either side heard nothing. The mission runner (colag_sim) supersedes it.
#include <cstdio>

#include "colag/platform/lockstep_executor.hpp"
#include "colag/platform/loopback_transport.hpp"
#include "colag/platform/monotonic_clock.hpp"
#include "colag/platform/readers.hpp"

using namespace colag;
using namespace std::chrono_literals;

namespace {
// Placeholder UAV: publishes odometry, counts the UGV statuses it hears.
class UavStubTask final : public platform::Task {
 public:
  explicit UavStubTask(platform::Transport& transport) : transport_(transport) {}
  const char* name() const override { return "uav_stub"; }
  Status init(TimePoint) override { return statuses_.attach(transport_); }
  void step(TimePoint now) override {
    msg::UgvStatus status;
    while (statuses_.pop(status))
      ++statuses_received_;
    msg::UavOdometry odom;
    odom.stamp = now;
    (void)transport_.publish(odom);
  }
  std::uint64_t statuses_received() const { return statuses_received_; }

 private:
  platform::Transport& transport_;
  platform::QueueReader<msg::UgvStatus, 16> statuses_;
  std::uint64_t statuses_received_ = 0;
};

// Placeholder UGV: listens to the UAV's odometry and publishes its status.
class UgvStubTask final : public platform::Task {
 public:
  explicit UgvStubTask(platform::Transport& transport) : transport_(transport) {}
  const char* name() const override { return "ugv_stub"; }
  Status init(TimePoint) override { return odometry_.attach(transport_); }
  void step(TimePoint now) override {
    msg::UgvStatus status;
    status.stamp = now;
    status.mode = odometry_.has_value() ? msg::UgvMode::kDriving : msg::UgvMode::kWaitingForInit;
    (void)transport_.publish(status);
  }
  std::uint64_t odometry_received() const { return odometry_.updates(); }

 private:
  platform::Transport& transport_;
  platform::LatestReader<msg::UavOdometry> odometry_;
};
}  // namespace

int main() {
  static platform::LoopbackTransport bus(/*seed=*/1);  // static: ~2 MB of in-flight slots
  platform::MonotonicClock wall;
  platform::LockstepExecutor executor(TimePoint{}, &wall);
  platform::TransportPump pump(bus);
  UavStubTask uav(bus);
  UgvStubTask ugv(bus);

  const platform::TaskEntry table[] = {
      {&pump, 10ms, 1ms},
      {&uav, 20ms, 5ms},
      {&ugv, 100ms, 5ms},
  };
  for (const auto& row : table) {
    if (Status s = executor.add(row); !s) {
      std::fprintf(stderr, "colag_smoke: %s\n", s.message());
      return 2;
    }
  }
  if (Status s = executor.init(); !s) {
    std::fprintf(stderr, "colag_smoke: init failed: %s\n", s.message());
    return 2;
  }
  executor.run_until(TimePoint{10s});

  std::printf("colag_smoke: 10 s simulated, lock-step executor, loopback transport\n");
  std::printf("%-10s %8s %9s %8s %12s\n", "task", "steps", "overruns", "skipped", "longest_us");
  const auto& sched = executor.schedule();
  for (std::size_t i = 0; i < sched.size(); ++i) {
    const auto& st = sched.stats(i);
    std::printf("%-10s %8llu %9llu %8llu %12.1f\n", st.name,
                static_cast<unsigned long long>(st.steps),
                static_cast<unsigned long long>(st.overruns),
                static_cast<unsigned long long>(st.skipped), to_seconds(st.longest_step) * 1e6);
  }
  const auto traffic = bus.stats();
  std::printf("messages: published %llu, delivered %llu, dropped %llu\n",
              static_cast<unsigned long long>(traffic.published),
              static_cast<unsigned long long>(traffic.delivered),
              static_cast<unsigned long long>(traffic.dropped));
  std::printf("UGV heard %llu UAV odometry samples; UAV heard %llu UGV statuses\n",
              static_cast<unsigned long long>(ugv.odometry_received()),
              static_cast<unsigned long long>(uav.statuses_received()));
  const bool ok = ugv.odometry_received() > 0 && uav.statuses_received() > 0;
  std::printf("%s\n", ok ? "OK" : "FAILED: a robot heard nothing");
  return ok ? 0 : 1;
}
