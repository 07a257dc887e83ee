#pragma once
/// @file operator.hpp
/// The operator's hands on one running controller: ctrl commands (power, emergency stop, stop)
/// and the operator wrench on the simulated handle, written through the `force` region at a
/// bounded rate. Used by the panel, the one-shot commands and the sequence player.
///
/// Errors: attaching throws HmiError with a message that says what to do (no controller for
/// that instance, and which instances do run). Commands that cannot be queued throw too. Nothing
/// here runs in the controller's cycle; every call is soft real-time at most.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/hmi/status.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace hapticctrl::hmi {

/// Every setup failure and refused command of the HMI; what() is meant for the operator.
class HmiError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Operator {
 public:
  /// Attaches to `instance` with one ctrl slot. With `want_force`, also claims `force`; if
  /// another live process writes it, the operator still works without force
  /// (force_unavailable() says why). Throws HmiError.
  Operator(const std::string& instance, bool want_force);

  /// Queues a ctrl command (retries a full queue for up to 100 ms). Throws HmiError.
  void send(shm::CtrlCode code);
  /// Sends `code`, then waits until `done(status)` holds or `timeout` passes. Returns whether
  /// it held.
  bool send_and_wait(shm::CtrlCode code, const std::function<bool(const ControllerStatus&)>& done,
                     std::chrono::milliseconds timeout);

  /// Sets the operator wrench to move towards (base frame, at the handle). False if refused:
  /// out of range / non-finite (ForceLimits), or force not available.
  bool request_force(const shm::Vector6& wrench);
  /// Moves the applied wrench towards the request and publishes it; call periodically
  /// (every few ms).
  void tick(TimePoint now);
  /// Ticks until the applied wrench reaches the request (bounded by the rate limit).
  void settle_force();
  /// Sets the simulated hand on the handle (shm::HandGrip; stiffness and damping 0: none),
  /// published with the wrench at the next tick(). Ramp it in and out (HandMotion): the core
  /// applies it as given. False if refused (out of range, or force not available).
  bool set_hand(const shm::HandGrip& hand);
  [[nodiscard]] const shm::HandGrip& hand() const noexcept { return hand_; }
  /// Lets go of the hand: its anchor stops, its stiffness and damping ramp to zero over
  /// HandMotion::kGripRamp (no force step). Blocks for the ramp; nothing to do without a hand.
  void release_hand();
  [[nodiscard]] const shm::ForceSlew& force() const noexcept { return slew_; }
  [[nodiscard]] bool force_available() const noexcept { return force_unavailable_.empty(); }
  [[nodiscard]] const std::string& force_unavailable() const noexcept { return force_unavailable_; }

  [[nodiscard]] ControllerStatus status() const;
  /// Whether the controller still runs (its lock is held and this segment is current).
  [[nodiscard]] bool controller_alive() const;
  [[nodiscard]] const shm::Segment& segment() const noexcept { return *segment_; }

 private:
  std::optional<shm::Segment> segment_;
  std::string force_unavailable_;
  shm::ForceSlew slew_;
  shm::HandGrip hand_{};
  bool hand_changed_ = false;
  TimePoint last_tick_ = kNotYet;
};

}  // namespace hapticctrl::hmi
