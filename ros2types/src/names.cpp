// Implements names.hpp: ROS 2 namespaces, DDS topic names, frames and stamps.
#include "hapticctrl/ros2types/names.hpp"

#include <stdexcept>

namespace hapticctrl::ros2types {
namespace {

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

bool digit(char c) {
  return c >= '0' && c <= '9';
}

}  // namespace

bool valid_namespace(std::string_view ns) {
  if (ns == "/") {
    return true;
  }
  if (ns.size() < 2 || ns.front() != '/' || ns.back() == '/') {
    return false;
  }
  bool token_start = true;
  for (const char c : ns.substr(1)) {
    if (c == '/') {
      if (token_start) {
        return false;  // "//"
      }
      token_start = true;
      continue;
    }
    if (!name_char(c) || (token_start && digit(c))) {
      return false;
    }
    token_start = false;
  }
  return true;
}

std::string checked_namespace(std::string_view ns) {
  if (!valid_namespace(ns)) {
    throw std::invalid_argument("'" + std::string(ns) +
                                "' is not a ROS 2 namespace (\"/\" then tokens of letters, digits "
                                "and '_' not starting with a digit, e.g. /lab/arm1)");
  }
  return std::string(ns);
}

std::string default_namespace(std::string_view instance) {
  std::string token;
  for (const char c : instance) {
    token += name_char(c) ? c : '_';
  }
  if (token.empty() || digit(token.front())) {
    token.insert(token.begin(), '_');
  }
  return "/hapticctrl/" + token;
}

std::string dds_topic(std::string_view ns, std::string_view name) {
  (void)checked_namespace(ns);
  std::string topic = "rt";
  topic += ns == "/" ? "" : ns;
  topic += '/';
  topic += name;
  return topic;
}

std::string base_frame(std::string_view ns) {
  return ns == "/" ? std::string("base") : std::string(ns.substr(1)) + "/base";
}

builtin_interfaces_msg_dds__Time_ stamp_of(std::int64_t ns) noexcept {
  const std::int64_t sec = ns >= 0 ? ns / 1'000'000'000 : (ns - 999'999'999) / 1'000'000'000;
  return {static_cast<int32_t>(sec), static_cast<uint32_t>(ns - sec * 1'000'000'000)};
}

}  // namespace hapticctrl::ros2types
