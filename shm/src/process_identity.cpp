// Implements process_identity.hpp: a process identity that survives pid reuse: pid plus the process
// start time.
#include "hapticctrl/shm/process_identity.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace hapticctrl::shm {
namespace {

constexpr unsigned kPidBits = 22;
constexpr std::uint64_t kPidMask = (std::uint64_t{1} << kPidBits) - 1;
constexpr std::uint64_t kStartMask = (std::uint64_t{1} << (64 - kPidBits)) - 1;

}  // namespace

std::optional<std::uint64_t> ProcessIdentity::start_ticks_of(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!stat || !std::getline(stat, line)) {
    return std::nullopt;
  }
  // The command name (field 2) may hold spaces and parentheses: parse after the last ')'.
  const auto close = line.rfind(')');
  if (close == std::string::npos) {
    return std::nullopt;
  }
  std::istringstream fields(line.substr(close + 2));
  std::string field;
  // Field 3 is the state; start time is field 22, i.e. the 20th after the ')'.
  for (int i = 3; i <= 22; ++i) {
    if (!(fields >> field)) {
      return std::nullopt;
    }
  }
  if (field.empty() || field.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return std::stoull(field);
}

ProcessIdentity ProcessIdentity::self() {
  const pid_t pid = getpid();
  return ProcessIdentity{pid, start_ticks_of(pid).value_or(0)};
}

bool ProcessIdentity::alive() const {
  const auto ticks = start_ticks_of(pid);
  return ticks.has_value() && *ticks == start_ticks;
}

std::uint64_t pack_identity(const ProcessIdentity& id) noexcept {
  return (static_cast<std::uint64_t>(id.pid) & kPidMask) |
         ((id.start_ticks & kStartMask) << kPidBits);
}

ProcessIdentity unpack_identity(std::uint64_t word) noexcept {
  return ProcessIdentity{static_cast<pid_t>(word & kPidMask), word >> kPidBits};
}

bool packed_identity_alive(std::uint64_t word) {
  if (word == 0) {
    return false;
  }
  const ProcessIdentity id = unpack_identity(word);
  const auto ticks = ProcessIdentity::start_ticks_of(id.pid);
  return ticks.has_value() && (*ticks & kStartMask) == id.start_ticks;
}

}  // namespace hapticctrl::shm
