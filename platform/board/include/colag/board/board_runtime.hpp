#pragma once
// What both board programs share: signal handling that stops the executor, the real-time
// set-up report, and the per-task statistics printed at exit.
#include <string>

#include "colag/platform/realtime_executor.hpp"

namespace colag::board {

// The command line both programs take: --config FILE [--check-config] [<seconds_flag> S].
struct ProgramArgs {
  std::string config_path;
  bool check_only = false;
  double seconds = -1.0;    // the value of seconds_flag; -1 when not given
  double time_scale = 1.0;  // --time-scale: simulated HAL only (SITL)
};
// False (usage or the missing --config printed, exit code 2) on anything else.
bool parse_program_args(int argc, char** argv, const char* program, const char* seconds_flag,
                        ProgramArgs& out);

// SIGINT and SIGTERM call exec.request_stop() (async-signal-safe); the program then cleans up
// in order (motors to zero first) instead of dying mid-command.
void stop_on_signals(platform::RealtimeExecutor& exec);

void print_realtime_setup(const char* program, const platform::RealtimeSetup& setup);
void print_task_stats(const char* program, const platform::Schedule& schedule);

}  // namespace colag::board
