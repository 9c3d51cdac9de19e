#pragma once
// Reading the board programs' YAML: typed values by key path, the first error kept as
// "FILE: key.path: problem", unknown keys reported. The robots' section readers use it.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <string>

#include "colag/common/time.hpp"
#include "colag/platform/task.hpp"

namespace colag::board {

// node[key] without yaml-cpp's surprises: absent (not null) when the node or the key is missing.
inline YAML::Node child(const YAML::Node& node, const char* key) {
  if (node && node.IsMap() && node[key]) return node[key];
  return YAML::Node(YAML::NodeType::Undefined);
}

// Reads a YAML file into `root`; false with "FILE: what yaml-cpp said" when it cannot.
inline bool load_yaml_file(const std::string& file, YAML::Node& root, std::string& error) {
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    error = file + ": " + e.what();
    return false;
  }
  return true;
}

// Walks a YAML document, reading typed values by key path and keeping the first error.
class Reader {
 public:
  Reader(const std::string& file, std::string& error) : file_(file), error_(error) {}

  bool ok() const { return error_.empty(); }
  const std::string& file() const { return file_; }
  void fail(const std::string& key, const std::string& problem) {
    if (ok()) error_ = file_ + ": " + key + ": " + problem;
  }

  // Checks that `node` (a map or absent) has only `allowed` keys.
  void only(const YAML::Node& node, const std::string& path, const std::set<std::string>& allowed) {
    if (!node) return;
    if (!node.IsMap()) return fail(path.empty() ? "(top level)" : path, "expected a mapping");
    std::set<std::string> seen;
    for (const auto& kv : node) {
      if (!kv.first.IsScalar())
        return fail(path.empty() ? "(top level)" : path, "a key is not a name");
      const std::string key = kv.first.as<std::string>();
      if (allowed.count(key) == 0) fail(join(path, key), "unknown key");
      // YAML keeps both of a duplicated key and reads the first: a silent surprise on a robot.
      if (!seen.insert(key).second) fail(join(path, key), "given twice");
    }
  }

  // A key without a default (what only the operator can know: which robot this is, its goal).
  void require(const YAML::Node& node, const std::string& path, const char* key) {
    if (!child(node, key)) fail(join(path, key), "required (no default)");
  }

  template <class T>
  void get(const YAML::Node& node, const std::string& path, const char* key, T& out, T lo, T hi) {
    const YAML::Node v = child(node, key);
    if (!v) return;
    T value{};
    try {
      value = v.as<T>();
    } catch (const YAML::Exception&) {
      return fail(join(path, key), std::string("expected ") + kind<T>());
    }
    if (!(value >= lo && value <= hi)) {
      return fail(join(path, key), "out of range [" + show(lo) + ", " + show(hi) + "]");
    }
    out = value;
  }
  void get(const YAML::Node& node, const std::string& path, const char* key, std::string& out) {
    const YAML::Node v = child(node, key);
    if (!v) return;
    if (!v.IsScalar()) return fail(join(path, key), "expected a string");
    out = v.as<std::string>();
  }
  void get(const YAML::Node& node, const std::string& path, const char* key, bool& out) {
    const YAML::Node v = child(node, key);
    if (!v) return;
    try {
      out = v.as<bool>();
    } catch (const YAML::Exception&) {
      fail(join(path, key), "expected true or false");
    }
  }
  // A loop's rate in Hz: its period changes, its budget keeps its share of the period.
  void rate(const YAML::Node& node, const std::string& path, const char* key,
            platform::LoopTiming& loop) {
    double hz = 0.0;
    const bool present = static_cast<bool>(child(node, key));
    get(node, path, key, hz, 0.1, 1000.0);
    if (present && ok()) loop = loop.at_period(period_of_hz(hz));
  }
  void millis(const YAML::Node& node, const std::string& path, const char* key, Duration& out,
              double lo, double hi) {
    double ms = to_seconds(out) * 1e3;
    get(node, path, key, ms, lo, hi);
    out = seconds(ms / 1e3);
  }
  // [x, y] or [x, y, z] (n values).
  bool vector(const YAML::Node& node, const std::string& path, const char* key, double* out,
              std::size_t n) {
    const YAML::Node v = child(node, key);
    if (!v) return false;
    if (!v.IsSequence() || v.size() != n) {
      fail(join(path, key), "expected a list of " + std::to_string(n) + " numbers");
      return false;
    }
    for (std::size_t i = 0; i < n; ++i) {
      try {
        out[i] = v[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(join(path, key), "expected a list of " + std::to_string(n) + " numbers");
        return false;
      }
      if (!std::isfinite(out[i])) fail(join(path, key), "not finite");
    }
    return ok();
  }
  // [[x, y], ...]: up to `max` points, each handed to add(x, y) in order once all are read.
  // False when absent or wrong (then nothing is added).
  template <class Add>
  bool points(const YAML::Node& node, const std::string& path, const char* key, std::size_t max,
              Add&& add) {
    const YAML::Node v = child(node, key);
    if (!v) return false;
    const std::string where = join(path, key);
    if (!v.IsSequence() || v.size() > max) {
      fail(where, "expected a list of at most " + std::to_string(max) + " [x, y] points");
      return false;
    }
    const auto read = [&](std::size_t i, double& x, double& y) {
      const YAML::Node p = v[i];
      try {
        if (p.IsSequence() && p.size() == 2) {
          x = p[0].as<double>();
          y = p[1].as<double>();
          if (std::isfinite(x) && std::isfinite(y)) return true;
        }
      } catch (const YAML::Exception&) {
      }
      fail(where + "[" + std::to_string(i) + "]", "expected [x, y], two finite numbers");
      return false;
    };
    double x = 0.0, y = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!read(i, x, y)) return false;
    for (std::size_t i = 0; i < v.size(); ++i) {
      read(i, x, y);
      add(x, y);
    }
    return ok();
  }

 private:
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  template <class T>
  static const char* kind() {
    if constexpr (std::is_integral_v<T>) return "an integer";
    return "a number";
  }
  template <class T>
  static std::string show(T v) {
    if constexpr (std::is_floating_point_v<T>) {
      std::string s = std::to_string(v);
      s.erase(s.find_last_not_of('0') + 1);
      if (s.back() == '.') s.pop_back();
      return s;
    } else {
      return std::to_string(v);
    }
  }
  std::string file_;
  std::string& error_;
};

// A path from a configuration file: relative paths are relative to the file's directory.
std::string relative_to(const std::string& config_file, const std::string& path);

}  // namespace colag::board
