#pragma once
// The main of a host program (colag_sim, colag_world, colag_bench): nothing escapes it as an
// exception. A library's exception (an allocation, CLI11, OpenCV writing a picture) ends the
// program with its message and the program's error exit code, not with abort() and a core.
#include <cstdio>
#include <exception>

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

}  // namespace colag::sim
