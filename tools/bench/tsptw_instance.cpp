#include "tsptw_instance.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace colag::programs {

bool read_tsptw(const std::string& path, uav::ScheduleProblem& out, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = "cannot open " + path;
    return false;
  }
  // Tokens with their line numbers; '#' starts a comment.
  std::string line;
  int line_no = 0;
  std::istringstream tokens;
  const auto next = [&](double& value, const char* what) {
    for (;;) {
      if (tokens >> value) return true;
      if (!tokens.eof()) {
        error = path + ":" + std::to_string(line_no) + ": expected a number (" + what + ")";
        return false;
      }
      if (!std::getline(in, line)) {
        error = path + ": file ends early, expected " + what;
        return false;
      }
      ++line_no;
      line = line.substr(0, line.find('#'));
      tokens.clear();
      tokens.str(line);
    }
  };
  double n_value = 0;
  if (!next(n_value, "the number of nodes")) return false;
  const auto n = static_cast<int>(n_value);
  if (n_value != n || n < 2 || n > static_cast<int>(uav::kMaxStops) + 1) {
    error = path + ": node count " + std::to_string(n_value) + " must be an integer in [2, " +
            std::to_string(uav::kMaxStops + 1) + "] (the depot plus up to kMaxStops)";
    return false;
  }
  out = uav::ScheduleProblem{};
  out.n = n - 1;
  out.closed = true;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (!next(out.travel[i][j], "a travel time")) return false;
      if (!std::isfinite(out.travel[i][j]) || out.travel[i][j] < 0) {
        error = path + ":" + std::to_string(line_no) + ": travel times must be finite and >= 0";
        return false;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!next(out.ready[i], "a ready time") || !next(out.due[i], "a due time")) return false;
    if (!(out.ready[i] <= out.due[i])) {
      error = path + ":" + std::to_string(line_no) + ": ready time after due time";
      return false;
    }
  }
  double extra = 0;
  if (tokens >> extra ||
      (std::getline(in, line) && line.find_first_not_of(" \t\r") != std::string::npos &&
       line.find_first_not_of(" \t\r") != line.find('#'))) {
    error = path + ": unexpected data after the time windows";
    return false;
  }
  return true;
}

}  // namespace colag::programs
