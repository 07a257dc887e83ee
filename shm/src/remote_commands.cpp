// Implements remote_commands.hpp: one rule for commands and forces from another host.
#include "hapticctrl/shm/remote_commands.hpp"

#include <array>
#include <cstdio>

namespace hapticctrl::shm {

std::string counters_json(const RemoteCommandCounters& c) {
  const auto get = [](const std::atomic<std::uint64_t>& v) {
    return static_cast<unsigned long long>(v.load());
  };
  std::array<char, 512> text{};
  std::snprintf(text.data(), text.size(),
                "\"commands_applied\":%llu,\"commands_refused\":%llu,\"commands_invalid\":%llu,"
                "\"commands_queue_full\":%llu,\"forces_accepted\":%llu,\"forces_refused\":%llu,"
                "\"forces_invalid\":%llu,\"force_timeouts\":%llu,\"malformed\":%llu",
                get(c.commands_applied), get(c.commands_refused), get(c.commands_invalid),
                get(c.commands_queue_full), get(c.forces_accepted), get(c.forces_refused),
                get(c.forces_invalid), get(c.force_timeouts), get(c.malformed));
  return text.data();
}

AttachOptions RemoteCommands::attach_options(bool allow_remote_commands) {
  AttachOptions options;
  options.ctrl_writer = true;
  if (allow_remote_commands) {
    options.write.push_back(RegionId::kForce);
  }
  return options;
}

RemoteCommands::RemoteCommands(const RemoteCommandSettings& settings, CtrlWriter* ctrl,
                               SeqlockCell<ForcePayload>* force) noexcept
    : settings_(settings), ctrl_(ctrl), force_(force), slew_(settings.force_limits) {}

void RemoteCommands::command(CtrlCode code, TimePoint now) noexcept {
  if (code == CtrlCode::kNone) {
    counters_.commands_invalid.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (code != CtrlCode::kEmergencyStop && !settings_.allow_remote_commands) {
    counters_.commands_refused.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (ctrl_ == nullptr || ctrl_->send(code, 0, to_ns(now)) != CtrlSendStatus::kQueued) {
    counters_.commands_queue_full.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  counters_.commands_applied.fetch_add(1, std::memory_order_relaxed);
}

void RemoteCommands::force(const Vector6& requested, TimePoint now) noexcept {
  if (!settings_.allow_remote_commands) {
    counters_.forces_refused.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (!slew_.set_target(requested)) {
    counters_.forces_invalid.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  last_force_ = now;
  force_active_ = true;
  counters_.forces_accepted.fetch_add(1, std::memory_order_relaxed);
}

void RemoteCommands::tick(TimePoint now) noexcept {
  const double dt = ticked_ ? to_seconds(now - last_tick_) : 0.0;
  last_tick_ = now;
  ticked_ = true;
  if (force_active_ && now - last_force_ > settings_.force_timeout) {
    slew_.set_target({});  // the sender went quiet: let go, at the same bounded rate
    force_active_ = false;
    counters_.force_timeouts.fetch_add(1, std::memory_order_relaxed);
  }
  if (slew_.step(dt) && force_ != nullptr) {
    force_->publish_quietly(ForcePayload{slew_.applied()}, to_ns(now));
  }
}

}  // namespace hapticctrl::shm
