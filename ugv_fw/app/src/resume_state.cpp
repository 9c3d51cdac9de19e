#include "colag/ugv/app/resume_state.hpp"

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <ctime>

namespace colag::ugv {

namespace {
constexpr const char* kMagic = "colag-ugv-state 1";
}

bool save_resume_state(const std::string& path, const Pose2& pose, std::string& error) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (f == nullptr) {
    error = tmp + ": cannot write";
    return false;
  }
  const bool written =
      std::fprintf(f, "%s %.6f %.6f %.6f\n", kMagic, pose.p.x(), pose.p.y(), pose.yaw_rad) > 0;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed || std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = path + ": cannot write";
    (void)std::remove(tmp.c_str());
    return false;
  }
  return true;
}

std::optional<ResumeState> load_resume_state(const std::string& path, double max_age_s,
                                             std::string& why) {
  why.clear();
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;  // no file: a first start
  if (!S_ISREG(st.st_mode)) {
    why = path + ": not a file";
    return std::nullopt;
  }
  ResumeState s;
  s.age_s = std::difftime(std::time(nullptr), st.st_mtime);
  if (s.age_s > max_age_s || s.age_s < -1.0) {
    char text[64];
    std::snprintf(text, sizeof text, ": %.0f s old (at most %.0f)", s.age_s, max_age_s);
    why = path + text;
    return std::nullopt;
  }
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (f == nullptr) {
    why = path + ": cannot read";
    return std::nullopt;
  }
  char magic[32] = {};
  char version[8] = {};
  double x = 0.0, y = 0.0, yaw = 0.0;
  const int n = std::fscanf(f, "%31s %7s %lf %lf %lf", magic, version, &x, &y, &yaw);
  std::fclose(f);
  if (n != 5 || std::string(magic) + " " + version != kMagic || !std::isfinite(x) ||
      !std::isfinite(y) || !std::isfinite(yaw)) {
    why = path + ": not a UGV state file";
    return std::nullopt;
  }
  s.pose = Pose2{Vec2(x, y), wrap_angle(yaw)};
  return s;
}

}  // namespace colag::ugv
