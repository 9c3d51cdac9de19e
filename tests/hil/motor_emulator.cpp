// A motor controller on a real CAN interface, for hardware-in-the-loop runs: the simulator's
// UgvBody (the wheel model and the controller side of the protocol --protocol names: colag,
// odrive or agilex_v2, with their default ids) stepped at 50 Hz in real time on SocketCAN. Stops
// after --seconds (so that the board's watchdog can be seen to trip) and, with --report FILE,
// writes the wheels' true travel there ("distance_m yaw_rad"): what the board's odometry is judged
// against, whatever commands reached it and when.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "colag/hal/can/can_base.hpp"
#include "colag/hal/linux/socketcan_bus.hpp"
#include "colag/platform/monotonic_clock.hpp"
#include "colag/sim/world/ugv_body.hpp"

int main(int argc, char** argv) {
  using namespace colag;
  std::string interface = "vcan0";
  double run_s = 5.0;
  std::string report;
  hal::can::BaseConfig base;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--interface") == 0) {
      interface = argv[i + 1];
    } else if (std::strcmp(argv[i], "--seconds") == 0) {
      run_s = std::atof(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--report") == 0) {
      report = argv[i + 1];
    } else if (std::strcmp(argv[i], "--protocol") == 0 &&
               hal::can::parse_base_protocol(argv[i + 1], base.protocol)) {
      // parsed into base.protocol
    } else {
      std::fprintf(stderr,
                   "usage: %s [--interface vcan0] [--seconds 5] [--report FILE] "
                   "[--protocol colag|odrive|agilex_v2]\n",
                   argv[0]);
      return 2;
    }
  }
  platform::MonotonicClock clock;
  linux_hal::SocketCanConfig cfg;
  cfg.interface = interface;
  for (const hal::can::IdFilter& f : hal::can::command_filters(base))  // the host's commands
    (void)cfg.filters.push_back({f.id, f.mask, f.extended});
  linux_hal::SocketCanBus bus(cfg, clock);
  if (const Status s = bus.open(); !s) {
    std::fprintf(stderr, "motor emulator: %s\n", s.message());
    return 1;
  }
  sim::UgvBodyConfig body_cfg;
  body_cfg.base = base;
  body_cfg.motion_noise_fraction = 0.0;  // a deterministic wheel model; encoder noise stays
  sim::UgvBody body(body_cfg, Pose2{}, 7);
  const Duration period = std::chrono::milliseconds(20);
  const TimePoint start = clock.now();
  TimePoint next = start;
  const TimePoint end = start + seconds(run_s);
  while (clock.now() < end) {
    next += period;
    std::this_thread::sleep_for(next - clock.now());
    body.step(clock.now(), 0.02, bus);
  }
  std::printf("motor emulator: stopped after %.1f s; true pose x %.3f y %.3f yaw %.3f, %.3f m\n",
              run_s, body.pose().p.x(), body.pose().p.y(), body.pose().yaw_rad, body.travelled_m());
  if (!report.empty()) {
    // Written to a temporary name and renamed: a reader never sees half a file.
    const std::string tmp = report + ".tmp";
    if (std::FILE* f = std::fopen(tmp.c_str(), "w")) {
      std::fprintf(f, "%.6f %.6f\n", body.travelled_m(), body.pose().yaw_rad);
      std::fclose(f);
      std::rename(tmp.c_str(), report.c_str());
    }
  }
  return 0;
}
