#pragma once
// What every board program does around its tasks: the command line, the configuration, the
// real-time set-up report, signals that stop the executor, and the per-task statistics at exit.
// A board program's main is one call: run_program(argc, argv, {name, flag, load, describe, run}).
#include <cstdio>
#include <string>

#include "colag/platform/realtime_executor.hpp"

namespace colag::board {

// Exit codes of every board program.
inline constexpr int kExitOk = 0;      // clean stop (SIGINT/SIGTERM, the time given, a test done)
inline constexpr int kExitDevice = 1;  // a device or DDS failed to start, or is missing
inline constexpr int kExitUsage = 2;   // a usage or configuration error

// The command line every board program takes: --config FILE [--check-config]
// [<seconds_flag> S] [--time-scale X].
struct ProgramArgs {
  std::string config_path;
  bool check_only = false;
  double seconds = -1.0;    // the value of seconds_flag; -1 when not given
  double time_scale = 1.0;  // --time-scale: simulated HAL only (SITL)
};
// False (usage or the missing --config printed) on anything else.
bool parse_program_args(int argc, char** argv, const char* program, const char* seconds_flag,
                        ProgramArgs& out);

template <class Config>
struct Program {
  const char* name;          // "ugv_fw": the prefix of every line it prints
  const char* seconds_flag;  // its one flag with a number of seconds ("--duration")
  bool (*load)(const std::string& path, Config& out, std::string& error);
  void (*describe)(const Config& config);  // one line on what the configuration says
  int (*run)(const Config& config, const ProgramArgs& args);  // returns the exit code
};

// The preamble of every board program: line-buffered output (even into a pipe or journald: a
// log must not lose its tail on SIGTERM), the command line, the configuration (errors: exit
// code 2), its description, --check-config; then the program's own run.
template <class Config>
int run_program(int argc, char** argv, const Program<Config>& program) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  ProgramArgs args;
  if (!parse_program_args(argc, argv, program.name, program.seconds_flag, args)) return kExitUsage;
  Config config;
  std::string error;
  if (!program.load(args.config_path, config, error)) {
    std::fprintf(stderr, "%s: %s\n", program.name, error.c_str());
    return kExitUsage;
  }
  program.describe(config);
  if (args.check_only) return kExitOk;
  return program.run(config, args);
}

// SIGINT and SIGTERM call exec.request_stop() (async-signal-safe); the program then cleans up
// in order (motors to zero first) instead of dying mid-command.
void stop_on_signals(platform::RealtimeExecutor& exec);

// "SCHED_FIFO on, mlockall off (not requested)": what was asked for and what was granted.
std::string describe_realtime_setup(const platform::RealtimeSetup& setup);
void print_realtime_setup(const char* program, const platform::RealtimeSetup& setup);
void print_task_stats(const char* program, const platform::Schedule& schedule);

}  // namespace colag::board
