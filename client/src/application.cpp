// Implements application.hpp: a session opened and set up with the refusals an application
// waits out retried, a quiet close, and the distance contacts are reported from.
#include "hapticctrl/client/application.hpp"

#include <algorithm>
#include <string>
#include <thread>

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::client {

bool retried(ErrorCode code, const RetryPolicy& policy) noexcept {
  return code == ErrorCode::kBusy || code == ErrorCode::kNoController ||
         code == ErrorCode::kTimeout || code == ErrorCode::kClosed ||
         (policy.reconnecting && code == ErrorCode::kRejected);
}

std::optional<Connection> connect_retrying(const Address& address, const ConnectOptions& options,
                                           const std::function<void(Connection&)>& setup,
                                           const std::function<bool()>& may_continue,
                                           const RetryPolicy& policy,
                                           const std::function<void(const ClientError&)>& say) {
  using Clock = MonotonicClock;
  constexpr std::chrono::milliseconds kCheck{50};
  const auto give_up = Clock::now() + policy.patience;
  std::string last_said;
  for (;;) {
    try {
      std::optional<Connection> c;
      c.emplace(address, options);
      setup(*c);
      return c;
    } catch (const ClientError& e) {
      const bool patient = policy.patience.count() == 0 || Clock::now() < give_up;
      if (!retried(e.code(), policy) || !patient) {
        throw;
      }
      if (last_said != e.what()) {
        last_said = e.what();
        say(e);
      }
    }
    for (auto waited = std::chrono::milliseconds(0); waited < policy.interval && may_continue();
         waited += kCheck) {
      std::this_thread::sleep_for(kCheck);
    }
    if (!may_continue()) {
      return std::nullopt;
    }
  }
}

void close_quietly(Connection& c) noexcept {
  if (!c.is_open()) {
    return;
  }
  try {
    c.close();
  } catch (const ClientError&) {
    // The controller may be gone already: the session ends either way.
  }
}

double contact_report_distance(const LinkStatistics& link) noexcept {
  return kContactNear + kReachSpeed * 2e-6 * std::max(link.rtt_mean_us, link.loop_delay_us);
}

}  // namespace hapticctrl::client
