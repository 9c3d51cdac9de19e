#pragma once
// What the main of every host program (colag_sim, colag_world, colag_bench) shares: nothing
// escapes it as an exception, a bad option is exit code 2, and numbers are checked with messages
// a user can read (CLI11 2.1's own validators print the largest double, 309 digits). A library's
// exception (an allocation, CLI11, OpenCV writing a picture) ends the program with its message and
// the program's error exit code, not with abort() and a core.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>

#include "colag/common/geometry.hpp"
#include "colag/hal/can/base_config.hpp"

namespace colag::sim {

// --ugv-base: the CAN protocol of the UGVs' bases (their emulators in the world).
inline CLI::Option* add_ugv_base_option(CLI::App& app, hal::can::BaseProtocol& out) {
  return app
      .add_option_function<std::string>(
          "--ugv-base",
          [&out](const std::string& name) { (void)hal::can::parse_base_protocol(name, out); },
          "the UGVs' bases: colag (our wheel protocol, default), odrive (two ODrive axes, CAN "
          "Simple) or agilex_v2 (an AgileX base, protocol V2)")
      ->check(CLI::IsMember({"colag", "odrive", "agilex_v2"}));
}

// --site WxH: the size of a generated site, metres (mission::MissionConfig::site).
inline CLI::Option* add_site_option(CLI::App& app, Vec2& out) {
  const auto parse = [](const std::string& s, Vec2& v) {
    const auto x = s.find('x');
    if (x == std::string::npos || x == 0 || x + 1 == s.size()) return false;
    char* end = nullptr;
    const double w = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + x) return false;
    const double h = std::strtod(s.c_str() + x + 1, &end);
    if (*end != '\0' || !(w > 0.0 && h > 0.0 && w < 1e9 && h < 1e9)) return false;
    v = Vec2(w, h);
    return true;
  };
  return app
      .add_option_function<std::string>(
          "--site", [&out, parse](const std::string& s) { (void)parse(s, out); },
          "a generated site of W x H metres (e.g. 200x200): the scenario's obstacles at the same "
          "density over it, the UGVs side by side along its north edge driving to the south one")
      ->check(CLI::Validator(
          [parse](std::string& s) -> std::string {
            Vec2 v;
            return parse(s, v) ? std::string{}
                               : "expected WxH in metres, e.g. 200x60, got '" + s + "'";
          },
          "WxH"));
}

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

// A seed: a whole number >= 0 (CLI11 would wrap -1 to 18446744073709551615).
inline const CLI::Validator kSeed(
    [](std::string& s) -> std::string {
      if (s.empty() || s.size() > 19 || s.find_first_not_of("0123456789") != std::string::npos)
        return "expected a whole number from 0 to 9999999999999999999, got '" + s + "'";
      return {};
    },
    "SEED");

// A number in (0, max].
inline CLI::Validator positive_up_to(double max) {
  char bound[32];
  std::snprintf(bound, sizeof bound, "%g", max);
  const std::string limit = bound;
  return CLI::Validator(
      [max, limit](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !(v > 0.0 && v <= max))
          return "expected a number > 0 and <= " + limit + ", got '" + s + "'";
        return {};
      },
      "(0, " + limit + "]");
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
