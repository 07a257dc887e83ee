#pragma once
/// @file connection.hpp
/// A client session with a hapticctrl controller over UDP/XDR (through hapticctrl-udp).
///
/// Two error regimes, as in the controller:
/// - setup and parameter calls block, and throw ClientError with a clear message;
/// - per-cycle calls (send_*, snapshot, statistics, wait_for_answer) are noexcept and allocate
///   nothing; they are safe in an application's real-time loop.
///
/// Threads: the connection owns one receive thread (answers, acknowledgements, keepalives);
/// callbacks from start_loop() run on it. Every public call is thread-safe.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#if __cplusplus >= 202002L
#include <span>
#endif
#include <string>
#include <string_view>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

/// Where a controller's bridge listens.
struct Address {
  std::string host = "127.0.0.1";
  std::uint16_t port = 5125;

  /// Parses "udpxdr://host:port", "host#port", "host:port" or "host" (port 5125).
  /// Throws ClientError(kInvalidArgument) naming the text.
  static Address parse(std::string_view text);
};

struct ConnectOptions {
  std::chrono::milliseconds connect_timeout{2000};  ///< HELLO retries (BUSY/NO_CONTROLLER too)
  std::chrono::milliseconds call_timeout{1000};     ///< each parameter call
  std::chrono::milliseconds retransmit_after{20};   ///< reliable frames
  std::uint32_t watchdog_ms = 0;                    ///< 0: the bridge's default
  bool keepalive = true;  ///< send KEEPALIVE when the application is silent for watchdog/4
  /// The session counts as closed when the bridge sends nothing for this long (killed, or
  /// cut off); parameter calls then throw kClosed saying so. 0: never. Longer than the bridge's
  /// default session watchdog (3 s), so that a link blackout of a few seconds is survived: the
  /// controller fades the coupling out meanwhile and ramps it back when frames flow again.
  std::chrono::milliseconds answer_timeout{4000};
  std::string client_name = "hapticctrl-client";
  /// For compatibility testing only: the protocol version and oldest version to advertise
  /// (0: this library's).
  std::uint32_t advertised_version = 0;
  std::uint32_t advertised_min_version = 0;
};

class Connection {
 public:
  /// Opens a session. Throws ClientError: kBusy (another client, after retrying for the
  /// connect timeout), kVersion (both versions in the message), kNoController, kTimeout,
  /// kTransport.
  explicit Connection(const Address& address, const ConnectOptions& options = {});
  Connection(Connection&&) noexcept;
  Connection& operator=(Connection&&) noexcept;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  /// Says BYE (best effort, bounded by the call timeout) and stops the receive thread.
  ~Connection();

  /// Ends the session now (acknowledged BYE). Throws ClientError(kTimeout) if unacknowledged.
  void close();

  // --- parameters and commands: reliable, blocking, throw ClientError -----------------------
  void set_time_step(double seconds);
  void set_force_factor(double factor);
  void set_speed_factor(double factor);
  void set_base_frame(const Pose7& frame);
  void set_observation_frame(const Pose7& frame);
  void set_indexing_mode(IndexingMode mode);
  void set_command_type(CommandType type);
  /// Attaches the virtual object (VIRTMECH): mass [kg], principal inertia [kg.m^2].
  void attach_object(double mass, const std::array<double, 3>& inertia);
  void detach_object();
  /// Coupling gains k_lin [N/m], b_lin [N.s/m], k_ang [N.m/rad], b_ang [N.m.s/rad]; 0: derived.
  void set_gains(double k_lin, double b_lin, double k_ang, double b_ang);
  /// Lower force [N] and torque [N.m] limits than the device's (0: the device's).
  void set_force_limits(double force, double torque);
  void set_watchdog(std::chrono::milliseconds timeout);
  void set_power(bool on);
  void emergency_stop();
  void reset_emergency_stop();

  // --- per cycle: noexcept, no allocation ------------------------------------------------------
  /// VIRTMECH: the virtual object's pose and twist (client frame). False if not sent.
  bool send_object_state(const Pose7& pose, const Vector6& twist) noexcept;
  /// IMPEDANCE: the wrench to render at the handle (client frame). False if not sent.
  bool send_wrench(const Vector6& wrench) noexcept;
  /// ARTICULAR: where each joint is to be [rad] and how fast its target moves [rad/s]; the
  /// controller's set points follow within the joints' ranges and its joint speed limit.
  /// False if not sent (a session without protocol 1.4's JOINT_CONTROL, a value out of range).
  bool send_joint_target(const Joints6& position, const Joints6& speed) noexcept;
  /// ARTICULAR_IMPEDANCE: a torque per joint [N.m], on top of the controller's gravity
  /// compensation. False if not sent (as send_joint_target).
  bool send_joint_torque(const Joints6& torque) noexcept;
  /// VIRTMECH: the contacts the object is in or near now (at most kMaxContacts; empty: none).
  /// They go out with the next object states (each changed contact at once, every one at least
  /// every 5 ms) and stay in force until replaced; the controller stiffens the coupling along
  /// them (docs/control.md). Nothing is changed unless kAccepted. `count` of them from
  /// `contacts` (nullptr with 0: none).
  ContactResult set_contacts(const Contact* contacts, std::size_t count) noexcept;
#if __cplusplus >= 202002L
  /// The same, from a span (C++20; the header needs no more than C++17 otherwise).
  ContactResult set_contacts(std::span<const Contact> contacts) noexcept {
    return set_contacts(contacts.data(), contacts.size());
  }
#endif
  /// The latest controller cycle received.
  [[nodiscard]] StateSnapshot snapshot() const noexcept;
  /// Blocks until an answer for a cycle after `after_cycle` arrives, or `timeout`.
  bool wait_for_answer(std::uint64_t after_cycle, std::chrono::nanoseconds timeout,
                       StateSnapshot& out) const noexcept;
  [[nodiscard]] LinkStatistics statistics() const noexcept;
  /// False once the session is closed (BYE, or the bridge ended it: controller stopped or
  /// bridge shutting down; parameter calls then throw kClosed with the bridge's reason).
  /// A Connection is one session: after a lost controller (snapshot().controller_lost(), or a
  /// fail-safe) open a new Connection to the same address and set it up again, as
  /// hapticctrl-demo and hapticctrl-mujoco do; the C API does it by itself (virtuose_api.md).
  [[nodiscard]] bool is_open() const noexcept;

  // --- callback style ---------------------------------------------------------------------------
  /// Calls `on_cycle` on the receive thread right after each answer (paced by the controller).
  /// The callback must not block; it may call the per-cycle functions and stop_loop() (not
  /// start_loop()).
  void start_loop(std::function<void(const StateSnapshot&)> on_cycle);
  /// Ends the callbacks: returns once a running one finished; called from the callback itself
  /// (VirtuoseAPI's virtStopLoop inside the periodic function), the loop ends when it returns.
  void stop_loop();

  // --- session facts ---------------------------------------------------------------------------
  [[nodiscard]] std::uint32_t features() const noexcept;
  [[nodiscard]] std::uint32_t watchdog_ms() const noexcept;
  [[nodiscard]] std::int64_t controller_period_ns() const noexcept;
  [[nodiscard]] std::uint32_t controller_version() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hapticctrl::client
