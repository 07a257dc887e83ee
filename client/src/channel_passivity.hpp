#pragma once
/// The client library's end of the two-port time-domain passivity of the coupling channel
/// (docs/control.md; Ryu, Artigas, Preusche).
///
/// Protocol 1.3 (the library closes the object's side of the coupling, local_coupling.hpp): the
/// channel's flow at this end is the handle as the answers give it (the handle image); the
/// client's side pushes it with a force (the object's spring for VIRTMECH, the application's
/// wrench for IMPEDANCE). The energy the channel gives this end may not exceed what the
/// controller reports having put in (ANSWER_COUPLED). When it would, a series passivity
/// controller lets the handle image give way along the client's force (it drifts), dissipating
/// the whole excess: for VIRTMECH as far as relaxing the object's spring in one step, with what
/// that cannot take cut from the object's wrench along the image's motion; the drift is given
/// back slowly while the budget allows. Unbounded but by that (bounded by the coupling's
/// damping until 2026-12-03, it let the balance break in contact: 4.0-8.6 J out for the core's
/// 2.3-3.1 J in at 10-20 ms, J1 review).
///
/// Protocol 1.1/1.2 (the controller computes the object's wrench): the flow is the object's
/// twist and the PC a damper on it, bounded so that the application's integration stays stable
/// and by the coupling's own damping.
///
/// Internal to the client library. Real-time contract: noexcept, no allocation; not
/// thread-safe (the connection serialises it).
#include <cstdint>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

class ChannelPassivity {
 public:
  /// The object's mass and largest principal inertia (virtAttachVO): they bound the 1.1 damper.
  void set_object(double mass, double inertia) noexcept;
  /// The controller's energy into the channel so far (J), from an answer.
  void on_controller_energy(double joules) noexcept;
  /// The coupling's own damping as the controller reports it (base frame: N·s/m, N·m·s/rad):
  /// the 1.1 damper never exceeds it.
  void on_coupling_damping(double linear, double angular) noexcept;
  void set_force_factor(double factor) noexcept;
  void set_speed_factor(double factor) noexcept;

  // --- protocol 1.3: the handle image's drift ----------------------------------------------
  /// Accounts a step of `dt` s during which the client's side pushed the handle image (moving
  /// with `flow`, the answers' handle twist) with `force`; `stretch` is the object's spring's
  /// stretch (handle image - object, client frame; zero for IMPEDANCE: no bound). Returns the
  /// energy the object's wrench must lose along `flow` this step (what the drift cannot take).
  double on_image_step(const Vector6& force, const Vector6& flow, const Vector6& stretch,
                       double dt) noexcept;
  /// Books what the caller cut from the object's wrench for that remainder (J).
  void on_cut(double joules) noexcept;
  /// The handle image's drift (client frame: linear, rotation vector) and its rate.
  [[nodiscard]] const Vector6& drift() const noexcept { return drift_; }
  [[nodiscard]] const Vector6& drift_rate() const noexcept { return drift_rate_; }

  // --- protocol 1.1/1.2: a damper on the object ----------------------------------------------
  /// The wrench the application gets for the controller's `wrench`: with the PC's damper.
  [[nodiscard]] Vector6 render(const Vector6& wrench) noexcept;
  /// Accounts the step the application just integrated: the object moved with `twist` for `dt`
  /// seconds under the wrench render() gave it last. Sets the damper for the next render().
  void on_step(const Vector6& twist, double dt) noexcept;

  /// The client's energy into the channel so far, in µJ modulo 2^32 (the wire's form).
  [[nodiscard]] std::uint32_t energy_in_uj() const noexcept;
  [[nodiscard]] double energy_in() const noexcept { return energy_in_; }
  [[nodiscard]] double energy_out() const noexcept { return energy_out_; }
  [[nodiscard]] std::uint64_t active_steps() const noexcept { return active_steps_; }

 private:
  /// Books one step's power (>= 0: in) and returns the excess of out over the controller's in.
  double book(double power, double dt) noexcept;

  double mass_ = 0.5;
  double inertia_ = 5e-4;
  double controller_in_ = 0.0;
  double energy_in_ = 0.0;   ///< J the client's side put into the channel
  double energy_out_ = 0.0;  ///< J the channel gave the client's side
  Vector6 drift_{};
  Vector6 drift_rate_{};
  Vector6 raw_{};       ///< 1.1: the controller's wrench at the last render()
  Vector6 rendered_{};  ///< 1.1: the wrench render() returned last (with the PC's damper)
  Vector6 twist_{};     ///< 1.1: the object's twist at the last step
  double alpha_linear_ = 0.0;
  double alpha_angular_ = 0.0;
  double coupling_linear_ = 0.0;   ///< the coupling's damping, N·s/m in the base frame
  double coupling_angular_ = 0.0;  ///< N·m·s/rad
  double force_factor_ = 1.0;
  double speed_factor_ = 1.0;
  std::uint64_t active_steps_ = 0;
};

}  // namespace hapticctrl::client
