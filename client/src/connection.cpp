// Connection: opening and closing a session, the control frames, the state and statistics.
// The protocol is ClientSession's (client_session.cpp), the I/O the shell's (connection_impl.hpp),
// the parameter calls are in connection_parameters.cpp.
#include "hapticctrl/client/connection.hpp"

#include <memory>
#include <optional>
#include <thread>
#include <utility>

#include "connection_impl.hpp"

namespace hapticctrl::client {

Connection::Connection(const Address& address, const ConnectOptions& options)
    : impl_(std::make_unique<Impl>(address, options)) {}
Connection::Connection(Connection&&) noexcept = default;
Connection& Connection::operator=(Connection&&) noexcept = default;

Connection::~Connection() {
  if (impl_ && impl_->is_open()) {
    try {
      impl_->bye();
    } catch (const ClientError&) {  // best effort: the bridge's watchdog closes it otherwise
    }
  }
}

void Connection::close() {
  if (impl_->is_open()) {
    impl_->bye();
  }
}

bool Connection::send_object_state(const Pose7& pose, const Vector6& twist) noexcept {
  std::optional<hcp_frame> frame;
  {
    const std::lock_guard lock(impl_->session_mutex);
    frame = impl_->session.object_frame(pose, twist, MonotonicClock::now());
  }
  const bool sent = impl_->send_control(frame);
  if (sent) {
    impl_->send_due_contacts();  // right after it: the bridge dates them with this state
  }
  return sent;
}

ContactResult Connection::set_contacts(const Contact* contacts, std::size_t count) noexcept {
  if (contacts == nullptr && count != 0) {
    return ContactResult::kInvalid;
  }
  const std::lock_guard lock(impl_->session_mutex);
  return impl_->session.set_contacts(std::span<const Contact>(contacts, count));
}

bool Connection::send_wrench(const Vector6& wrench) noexcept {
  std::optional<hcp_frame> frame;
  {
    const std::lock_guard lock(impl_->session_mutex);
    frame = impl_->session.wrench_frame(wrench, MonotonicClock::now());
  }
  const bool sent = impl_->send_control(frame);
  if (sent) {
    impl_->send_due_contacts();  // an IMPEDANCE client's surfaces (protocol 1.3)
  }
  return sent;
}

bool Connection::send_joint_target(const Joints6& position, const Joints6& speed) noexcept {
  std::optional<hcp_frame> frame;
  {
    const std::lock_guard lock(impl_->session_mutex);
    frame = impl_->session.joint_target_frame(position, speed, MonotonicClock::now());
  }
  return impl_->send_control(frame);
}

bool Connection::send_joint_torque(const Joints6& torque) noexcept {
  std::optional<hcp_frame> frame;
  {
    const std::lock_guard lock(impl_->session_mutex);
    frame = impl_->session.joint_torque_frame(torque, MonotonicClock::now());
  }
  return impl_->send_control(frame);
}

StateSnapshot Connection::snapshot() const noexcept {
  const std::lock_guard lock(impl_->session_mutex);
  return impl_->session.latest();
}

bool Connection::wait_for_answer(std::uint64_t after_cycle, std::chrono::nanoseconds timeout,
                                 StateSnapshot& out) const noexcept {
  std::unique_lock lock(impl_->session_mutex);
  const bool got = impl_->answer_cv.wait_for(lock, timeout, [&] {
    return impl_->session.latest().valid && impl_->session.latest().cycle > after_cycle;
  });
  out = impl_->session.latest();
  return got;
}

LinkStatistics Connection::statistics() const noexcept {
  const std::lock_guard lock(impl_->session_mutex);
  return impl_->session.statistics();
}

bool Connection::is_open() const noexcept {
  return impl_->is_open();
}

void Connection::start_loop(std::function<void(const StateSnapshot&)> on_cycle) {
  const std::lock_guard lock(impl_->loop_mutex);
  impl_->on_cycle = std::move(on_cycle);
}

void Connection::stop_loop() {
  if (std::this_thread::get_id() == impl_->receiver.get_id()) {
    impl_->loop_stop_requested.store(true);  // from the callback: ends when it returns
    return;
  }
  const std::lock_guard lock(impl_->loop_mutex);  // returns once a running callback finished
  impl_->on_cycle = nullptr;
}

std::uint32_t Connection::features() const noexcept {
  const std::lock_guard lock(impl_->session_mutex);
  return impl_->session.features();
}
std::uint32_t Connection::watchdog_ms() const noexcept {
  const std::lock_guard lock(impl_->session_mutex);
  return impl_->session.watchdog_ms();
}
std::int64_t Connection::controller_period_ns() const noexcept {
  const std::lock_guard lock(impl_->session_mutex);
  return to_ns(impl_->session.controller_period());
}
std::uint32_t Connection::controller_version() const noexcept {
  const std::lock_guard lock(impl_->session_mutex);
  return impl_->session.controller_version();
}

}  // namespace hapticctrl::client
