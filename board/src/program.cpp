#include "colag/board/program.hpp"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace colag::board {

namespace {
platform::RealtimeExecutor* g_exec = nullptr;
extern "C" void on_signal(int) {
  if (g_exec != nullptr) g_exec->request_stop();
}
}  // namespace

bool parse_program_args(int argc, char** argv, const char* program, const char* seconds_flag,
                        ProgramArgs& out) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--config") == 0 && i + 1 < argc) {
      out.config_path = argv[++i];
    } else if (std::strcmp(argv[i], "--check-config") == 0) {
      out.check_only = true;
    } else if (std::strcmp(argv[i], seconds_flag) == 0 && i + 1 < argc) {
      out.seconds = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--time-scale") == 0 && i + 1 < argc) {
      out.time_scale = std::atof(argv[++i]);
      if (!(out.time_scale >= 0.1 && out.time_scale <= 20.0)) {
        std::fprintf(stderr, "%s: --time-scale must be in [0.1, 20]\n", program);
        return false;
      }
    } else {
      std::fprintf(stderr,
                   "usage: %s --config FILE.yaml [--check-config] [%s S] [--time-scale X (SITL)]\n",
                   program, seconds_flag);
      return false;
    }
  }
  if (out.config_path.empty()) {
    std::fprintf(stderr, "%s: --config FILE.yaml is required\n", program);
    return false;
  }
  return true;
}

void stop_on_signals(platform::RealtimeExecutor& exec) {
  g_exec = &exec;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

std::string describe_realtime_setup(const platform::RealtimeSetup& setup) {
  const auto state = [](bool requested, const Status& s) -> std::string {
    if (!requested) return "off (not requested)";
    return s ? "on" : s.message();
  };
  return "SCHED_FIFO " + state(setup.fifo_requested, setup.fifo) + ", mlockall " +
         state(setup.memory_lock_requested, setup.memory_lock);
}

void print_realtime_setup(const char* program, const platform::RealtimeSetup& setup) {
  std::printf("%s: %s\n", program, describe_realtime_setup(setup).c_str());
}

void print_task_stats(const char* program, const platform::Schedule& schedule) {
  std::printf("%s: %-14s %10s %9s %8s %12s\n", program, "task", "steps", "overruns", "skipped",
              "longest ms");
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    const platform::TaskStats& s = schedule.stats(i);
    std::printf("%s: %-14s %10llu %9llu %8llu %12.3f\n", program, s.name,
                static_cast<unsigned long long>(s.steps),
                static_cast<unsigned long long>(s.overruns),
                static_cast<unsigned long long>(s.skipped), to_seconds(s.longest_step) * 1e3);
  }
}

}  // namespace colag::board
