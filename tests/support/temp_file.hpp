#pragma once
// A test's input file: `text` written to the test temp directory under `name`, with the pid in
// the path (ctest runs test processes in parallel, and two suites may run at once); removed when
// the test program ends.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace colag::test {

inline std::string write_temp_file(const std::string& name, const std::string& text) {
  static struct Written {
    std::vector<std::string> paths;
    ~Written() {
      for (const std::string& p : paths)
        std::remove(p.c_str());
    }
  } written;
  std::string path = ::testing::TempDir() + "colag_" + std::to_string(::getpid()) + "_" + name;
  std::ofstream(path) << text;
  written.paths.push_back(path);
  return path;
}

}  // namespace colag::test
