// Implements run_summary.hpp: the end-of-run summary of hapticctrl-mujoco as JSON.
#include "hapticctrl/mujoco/run_summary.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>

namespace hapticctrl::mujoco {
namespace {

/// printf into a string (the summary's numbers keep their fixed formats; the compiler checks
/// the arguments against the format).
__attribute__((format(printf, 1, 2))) std::string format(const char* fmt, ...) {
  std::va_list args;
  va_start(args, fmt);
  std::va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, args);
  va_end(args);
  std::string out(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::vsnprintf(out.data(), out.size(), fmt, again);
  va_end(again);
  out.pop_back();
  return out;
}

using Count = unsigned long long;  // printf's %llu

}  // namespace

void EngineLoad::add(std::int64_t ns) noexcept {
  ++steps;
  cpu_ns += ns;
  cpu_max_ns = std::max(cpu_max_ns, ns);
}

double EngineLoad::mean_us() const noexcept {
  return steps > 0 ? static_cast<double>(cpu_ns) / static_cast<double>(steps) / 1e3 : 0.0;
}

std::string summary_json(const RunSummary& s) {
  const client::Pose7& p = s.body_pose;
  const auto& f = s.contact_force;
  const client::Vector6& w = s.coupling_wrench;
  std::string out = format(
      "{\"ended\":\"%s\",\"body\":\"%s\",\"mass\":%.6g,\"timestep\":%.6g,"
      "\"body_pose\":[%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f],"
      "\"contact_force\":[%.4f,%.4f,%.4f],\"coupling_wrench\":[%.4f,%.4f,%.4f,%.4f,%.4f,%.4f],"
      "\"steps\":%llu,\"steps_per_second\":%.1f,\"model_steps_per_second\":%.1f,"
      "\"steps_dropped\":%llu,\"steps_paused\":%llu,\"catch_ups\":%llu,"
      "\"cpu_us_per_step_mean\":%.2f,\"cpu_us_per_step_max\":%.1f,"
      "\"contact_reports\":%llu,\"contacts_supported\":%s,\"instabilities\":%d,"
      "\"reconnections\":%llu,\"powered\":%s,\"gripping\":%s,",
      s.ended.c_str(), s.body.c_str(), s.mass, s.timestep, p[0], p[1], p[2], p[3], p[4], p[5], p[6],
      f[0], f[1], f[2], w[0], w[1], w[2], w[3], w[4], w[5], static_cast<Count>(s.steps),
      s.steps_per_second, s.timestep > 0.0 ? 1.0 / s.timestep : 0.0,
      static_cast<Count>(s.steps_dropped), static_cast<Count>(s.steps_paused),
      static_cast<Count>(s.catch_ups), s.load.mean_us(),
      static_cast<double>(s.load.cpu_max_ns) / 1e3, static_cast<Count>(s.contact_reports),
      s.contacts_supported ? "true" : "false", s.instabilities, static_cast<Count>(s.reconnections),
      s.powered ? "true" : "false", s.gripping ? "true" : "false");
  const char* separator = "";
  out += "\"bodies\":{";
  for (const auto& [name, at] : s.bodies) {
    out += format("%s\"%s\":[%.6f,%.6f,%.6f]", separator, name.c_str(), at[0], at[1], at[2]);
    separator = ",";
  }
  separator = "";
  out += "},\"joints\":{";
  for (const auto& [name, q] : s.joints) {
    out += format("%s\"%s\":%.6f", separator, name.c_str(), q);
    separator = ",";
  }
  return out + "}}";
}

}  // namespace hapticctrl::mujoco
