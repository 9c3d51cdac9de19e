#pragma once
// The main of a host program (colag_sim, colag_world, colag_bench): nothing escapes it as an
// exception, and a bad option is exit code 2. A library's exception (an allocation, CLI11, OpenCV
// writing a picture) ends the program with its message and the program's error exit code, not with
// abort() and a core.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <optional>

namespace colag::sim {

template <class Run>
int guarded_main(const char* program, int error_code, Run&& run) {
  try {
    return run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unexpected error\n", program);
  }
  return error_code;
}

// CLI11's parse with our exit codes (CLI11's own are 100+): nullopt to go on; 0 after --help;
// 2, the usage error of every program, after a bad option (CLI11 prints what was wrong).
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return std::nullopt;
}

}  // namespace colag::sim
