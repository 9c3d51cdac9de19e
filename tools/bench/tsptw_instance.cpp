#include "tsptw_instance.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace colag::programs {

bool read_tsptw(const std::string& path, uav::ScheduleProblem& out, std::string& error) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    error = path + ": not a file";
    return false;
  }
  std::ifstream in(path);
  if (!in) {
    error = "cannot open " + path;
    return false;
  }
  return parse_tsptw(in, path, out, error);
}

bool parse_tsptw(std::istream& in, const std::string& path, uav::ScheduleProblem& out,
                 std::string& error) {
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
  // The range first: converting 1e12 to int would be undefined.
  if (!(n_value >= 2 && n_value <= static_cast<double>(uav::kMaxStops + 1)) ||
      n_value != std::floor(n_value)) {
    error = path + ": node count " + std::to_string(n_value) + " must be an integer in [2, " +
            std::to_string(uav::kMaxStops + 1) + "] (the depot plus up to kMaxStops)";
    return false;
  }
  const auto n = static_cast<int>(n_value);
  const auto time_ok = [](double t) { return std::isfinite(t) && t >= 0 && t <= kMaxTsptwTime_s; };
  const auto fail_at = [&](const char* problem) {
    error = path;
    error += ':';
    error += std::to_string(line_no);
    error += ": ";
    error += problem;
    return false;
  };
  out = uav::ScheduleProblem{};
  out.n = n - 1;
  out.closed = true;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (!next(out.travel[i][j], "a travel time")) return false;
      if (!time_ok(out.travel[i][j]))
        return fail_at("travel times must be finite, >= 0 and <= 1e9");
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!next(out.ready[i], "a ready time") || !next(out.due[i], "a due time")) return false;
    if (!time_ok(out.ready[i]) || !time_ok(out.due[i]))
      return fail_at("time windows must be finite, >= 0 and <= 1e9");
    if (!(out.ready[i] <= out.due[i])) return fail_at("ready time after due time");
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
