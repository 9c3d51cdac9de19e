#include "mission_pool.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

namespace colag::programs {

std::string MissionSpec::key() const {
  return scenario + "/" + std::to_string(ugvs) + "/" + ablation + (self_perception ? "/sp" : "") +
         (faults == "none" ? "" : "/" + faults) +
         (uavs == 1 ? "" : "/uavs" + std::to_string(uavs)) + (scouting ? "/scouting" : "");
}

void Mean::add(double v) {
  if (std::isfinite(v)) {
    sum += v;
    sum_sq += v * v;
    ++n;
  }
}
double Mean::get() const {
  return n > 0 ? sum / n : NAN;
}
double Mean::half95() const {
  if (n < 2) return NAN;
  // t(0.975, dof) for dof 1..10, then towards the normal's 1.96.
  static constexpr double kT[] = {12.71, 4.30, 3.18, 2.78, 2.57, 2.45, 2.36, 2.31, 2.26, 2.23};
  const int dof = n - 1;
  const double t = dof <= 10 ? kT[dof - 1] : (dof <= 30 ? 2.09 : 1.96);
  const double mean = sum / n;
  const double var = std::max(0.0, (sum_sq - n * mean * mean) / (n - 1));
  return t * std::sqrt(var / n);
}

std::string sim_path(const std::string& explicit_path) {
  if (!explicit_path.empty()) return explicit_path;
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return "colag_sim";
  std::string dir(self, static_cast<std::size_t>(n));
  return dir.substr(0, dir.rfind('/')) + "/colag_sim";
}

namespace {
bool start(MissionRun& r, const std::string& sim, double max_time, int threads) {
  std::vector<std::string> args = {sim,          "--quiet",
                                   "--threads",  std::to_string(threads),
                                   "--scenario", r.spec.scenario,
                                   "--ugvs",     std::to_string(r.spec.ugvs),
                                   "--seed",     std::to_string(r.seed),
                                   "--ablation", r.spec.ablation,
                                   "--max-time", std::to_string(max_time),
                                   "--json",     r.json_path};
  if (r.spec.self_perception) args.push_back("--self-perception");
  if (r.spec.uavs != 1) args.insert(args.end(), {"--uavs", std::to_string(r.spec.uavs)});
  if (r.spec.scouting) args.insert(args.end(), {"--scouting", "on"});
  args.insert(args.end(), {"--world", r.spec.world});
  args.insert(args.end(), r.spec.fault_args.begin(), r.spec.fault_args.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  return posix_spawn(&r.pid, sim.c_str(), nullptr, nullptr, argv.data(), environ) == 0;
}
}  // namespace

bool run_missions(std::vector<MissionRun>& runs, const std::string& sim, int jobs,
                  double max_time_s) {
  if (access(sim.c_str(), X_OK) != 0) {
    std::fprintf(stderr, "colag_bench: cannot run %s\n", sim.c_str());
    return false;
  }
  // A directory of its own, made new: a name from the pid alone was reused across runs (CI runs
  // the suite several times in one container), and a mission that wrote nothing then read another
  // run's JSON as its own.
  char dir_template[] = "/tmp/colag_bench.XXXXXX";
  if (mkdtemp(dir_template) == nullptr) {
    std::fprintf(stderr, "colag_bench: cannot make a directory in /tmp\n");
    return false;
  }
  const std::string dir = dir_template;
  for (std::size_t i = 0; i < runs.size(); ++i)
    runs[i].json_path = dir + "/run" + std::to_string(i) + ".json";
  const auto remove_dir = [&] {
    for (const MissionRun& r : runs)
      std::remove(r.json_path.c_str());
    rmdir(dir.c_str());
  };
  // Each mission gets an equal share of the cores (its results do not depend on it).
  const int threads =
      std::clamp(static_cast<int>(std::thread::hardware_concurrency()) / jobs, 1, 8);
  std::size_t next = 0, done = 0;
  int active = 0;
  while (done < runs.size()) {
    while (active < jobs && next < runs.size()) {
      if (!start(runs[next], sim, max_time_s, threads)) {
        std::fprintf(stderr, "colag_bench: cannot start %s\n", sim.c_str());
        remove_dir();
        return false;
      }
      ++next;
      ++active;
    }
    int status = 0;
    const pid_t pid = wait(&status);
    if (pid < 0) break;
    --active;
    ++done;
    for (MissionRun& r : runs) {
      if (r.pid != pid) continue;
      // colag_sim exits 1 when the mission ran but a UGV collided or fell short: that is a
      // result to count; 2 (an input error), another code or a signal is a mission that did not
      // run.
      r.ok = WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 1);
      if (r.ok) {
        std::ifstream in(r.json_path);
        r.result = nlohmann::json::parse(in, nullptr, false);
        r.ok = !r.result.is_discarded();
      }
      std::printf("  [%3zu/%zu] %-34s seed %d %s\n", done, runs.size(), r.spec.key().c_str(),
                  r.seed, r.ok ? "" : "FAILED");
      std::fflush(stdout);
    }
  }
  remove_dir();
  return true;
}

}  // namespace colag::programs
