#pragma once
// What both board programs share: signal handling that stops the executor, the real-time
// set-up report, and the per-task statistics printed at exit.
#include "colag/platform/realtime_executor.hpp"

namespace colag::board {

// SIGINT and SIGTERM call exec.request_stop() (async-signal-safe); the program then cleans up
// in order (motors to zero first) instead of dying mid-command.
void stop_on_signals(platform::RealtimeExecutor& exec);

void print_realtime_setup(const char* program, const platform::RealtimeSetup& setup);
void print_task_stats(const char* program, const platform::Schedule& schedule);

}  // namespace colag::board
