#include "colag/hal/ros2/ros2_names.hpp"

namespace colag::hal::ros2 {

namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && s.front() == '/')
    s.remove_prefix(1);
  while (!s.empty() && s.back() == '/')
    s.remove_suffix(1);
  return s;
}

}  // namespace

std::string ros2_dds_topic(std::string_view ns, std::string_view name) {
  std::string topic = "rt/";
  ns = trimmed(ns);
  if (!ns.empty()) {
    topic += ns;
    topic += '/';
  }
  topic += trimmed(name);
  return topic;
}

}  // namespace colag::hal::ros2
