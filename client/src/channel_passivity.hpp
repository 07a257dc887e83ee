#pragma once
/// The client library's end of the two-port time-domain passivity of the coupling channel
/// (docs/control.md; Ryu, Artigas, Preusche). The channel hands the application's object the
/// coupling wrench; the energy it gives the object may not exceed what the controller reports
/// having put in (ANSWER_TIMED). When it would, a passivity controller adds a damper on the
/// object's motion to the wrench the application gets, dissipating the excess, bounded so that
/// the application's integration stays stable and by the coupling's own damping (so that it
/// never chatters the wrench). The application needs no code for it.
///
/// Internal to the client library. Real-time contract: noexcept, no allocation; not
/// thread-safe (the connection serialises it).
#include <cstdint>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

class ChannelPassivity {
 public:
  /// The object's mass and largest principal inertia (virtAttachVO): they bound the damper.
  void set_object(double mass, double inertia) noexcept;
  /// The controller's energy into the channel so far (J), from an answer.
  void on_controller_energy(double joules) noexcept;
  /// The coupling's own damping as the controller reports it (base frame: N·s/m, N·m·s/rad)
  /// and the factors that turn it into the application's units: the PC's damper never exceeds
  /// it (0: no such bound, the integration's alone).
  void on_coupling_damping(double linear, double angular) noexcept;
  void set_force_factor(double factor) noexcept;
  void set_speed_factor(double factor) noexcept;
  /// The wrench the application gets for the controller's `wrench`: with the PC's damper.
  [[nodiscard]] Vector6 render(const Vector6& wrench) noexcept;
  /// Accounts the step the application just integrated: the object moved with `twist` for `dt`
  /// seconds under the wrench render() gave it last. Sets the damper for the next render().
  void on_step(const Vector6& twist, double dt) noexcept;
  /// The object's energy into the channel so far, in µJ modulo 2^32 (the wire's form).
  [[nodiscard]] std::uint32_t energy_in_uj() const noexcept;
  [[nodiscard]] double energy_in() const noexcept { return energy_in_; }
  [[nodiscard]] double energy_out() const noexcept { return energy_out_; }
  [[nodiscard]] std::uint64_t active_steps() const noexcept { return active_steps_; }

 private:
  double mass_ = 0.5;
  double inertia_ = 5e-4;
  double controller_in_ = 0.0;
  double energy_in_ = 0.0;   ///< J the object put into the channel
  double energy_out_ = 0.0;  ///< J the channel gave the object
  Vector6 raw_{};            ///< the controller's wrench at the last render(): the channel's
  Vector6 rendered_{};       ///< the wrench render() returned last (with the PC's damper)
  Vector6 twist_{};          ///< the object's twist at the last step
  double alpha_linear_ = 0.0;
  double alpha_angular_ = 0.0;
  double coupling_linear_ = 0.0;   ///< the coupling's damping, N·s/m in the base frame
  double coupling_angular_ = 0.0;  ///< N·m·s/rad
  double force_factor_ = 1.0;
  double speed_factor_ = 1.0;
  std::uint64_t active_steps_ = 0;
};

}  // namespace hapticctrl::client
