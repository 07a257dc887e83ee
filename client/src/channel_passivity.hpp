#pragma once
/// The client library's end of the two-port time-domain passivity of the coupling channel
/// (docs/control.md; Ryu, Artigas, Preusche). The application needs no code for it.
///
/// VIRTMECH: the channel hands the object a wrench (the controller's, or from protocol 1.3, while
/// a contact is in force, the library's own on the object's state, local_coupling.hpp) and takes
/// its motion: the energy the wrench gives the object may not exceed what the controller reports
/// having put in (compared a loop late: the report covers the object's motion up to then). When
/// it would, a passivity controller adds a damper on the object's motion within what the
/// application's integration bears. Free, the damper takes at most the wrench's share along the
/// motion (it never pushes against the motion itself: beyond it, it shook a resting weighted
/// object's support between 1.4 and 7.4 N, J1 2026-12-03). Held by a contact (protocol 1.3), it
/// takes the whole excess the integration bears (up to stopping the object's step; on its
/// rotation half of that, where the application's own contact terms act unseen), even
/// against the motion: bounded there, the balance broke (4.0-8.6 J out for the core's 2.3-3.1 J
/// in at 10-20 ms, J1 review). What it cannot take stays owed and is damped on the next steps.
///
/// IMPEDANCE (protocol 1.3): the channel hands the application the handle's motion (the answers'
/// handle twist) and takes its wrench: the energy the handle's motion gives the application's
/// wrench may not exceed what the controller put in. When it would, the handle image the
/// application sees gives way along its wrench (a series controller: the image drifts),
/// dissipating the whole excess; the drift is given back slowly while the budget allows.
///
/// Internal to the client library. Real-time contract: noexcept, no allocation; not
/// thread-safe (the connection serialises it).
#include <array>
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

class ChannelPassivity {
 public:
  /// The object's mass and smallest principal moment of inertia (virtAttachVO): they bound the
  /// damper.
  void set_object(double mass, double inertia) noexcept;
  /// The controller's energy into the channel so far (J), from an answer.
  void on_controller_energy(double joules) noexcept;
  /// How much of a contact is in force (0..1, protocol 1.3): held by a surface, the object takes
  /// the whole damper the excess asks (within its integration); free, the damper stays within
  /// the wrench's share along the motion.
  void set_contact_share(double share) noexcept;
  /// The coupling loop (s): the controller's report covers the object's motion up to this long
  /// ago, so the object's output of a loop ago is what it must cover (0: now).
  void set_loop(double seconds) noexcept;

  // --- VIRTMECH: the object's port --------------------------------------------------------------
  /// The wrench the application gets for the channel's `wrench`: with the PC's damper.
  [[nodiscard]] Vector6 render(const Vector6& wrench) noexcept;
  /// Accounts the step the application just integrated at `now`: the object moved with
  /// `twist` for `dt` seconds under the wrench render() gave it last. Sets the damper for the
  /// next render(), within what an integration that holds a wrench for `held` seconds bears
  /// (`held` >= dt: the application may integrate several steps with one wrench).
  void on_step(const Vector6& twist, double dt, double held, TimePoint now) noexcept;

  // --- IMPEDANCE (protocol 1.3): the handle image ----------------------------------------------
  /// Accounts a step of `dt` s during which the application's `wrench` pushed the handle image
  /// moving with `flow` (the answers' handle twist), and sets the drift for the next view.
  void on_image_step(const Vector6& wrench, const Vector6& flow, double dt) noexcept;
  /// The handle image's drift (client frame: linear, rotation vector) and its rate.
  [[nodiscard]] const Vector6& drift() const noexcept { return drift_; }
  [[nodiscard]] const Vector6& drift_rate() const noexcept { return drift_rate_; }

  /// The client's energy into the channel so far, in µJ modulo 2^32 (the wire's form).
  [[nodiscard]] std::uint32_t energy_in_uj() const noexcept;
  [[nodiscard]] double energy_in() const noexcept { return energy_in_; }
  [[nodiscard]] double energy_out() const noexcept { return energy_out_; }
  [[nodiscard]] std::uint64_t active_steps() const noexcept { return active_steps_; }

 private:
  /// Books one step's power (>= 0: out of the channel) and returns the excess of out over the
  /// controller's in.
  double book_output(double power, double dt) noexcept;

  /// The object's output (before the PC) as it was, one entry per step.
  struct Past {
    TimePoint at;
    double out = 0.0;
  };
  [[nodiscard]] double output_ago(TimePoint now) const noexcept;

  std::array<Past, 1024> past_{};
  std::size_t past_next_ = 0;
  std::size_t past_count_ = 0;
  Duration loop_{};
  double dissipated_ = 0.0;  ///< J the PC took out (energy_out_ is net)
  double mass_ = 0.5;
  double inertia_ = 5e-4;
  double controller_in_ = 0.0;
  double energy_in_ = 0.0;   ///< J the client's side put into the channel
  double energy_out_ = 0.0;  ///< J the channel gave the client's side
  Vector6 raw_{};            ///< the channel's wrench at the last render()
  Vector6 rendered_{};       ///< the wrench render() returned last (with the PC's terms)
  Vector6 twist_{};          ///< the object's twist at the last step
  double alpha_linear_ = 0.0;
  double alpha_angular_ = 0.0;
  double contact_share_ = 0.0;
  Vector6 drift_{};
  Vector6 drift_rate_{};
  std::uint64_t active_steps_ = 0;
};

}  // namespace hapticctrl::client
