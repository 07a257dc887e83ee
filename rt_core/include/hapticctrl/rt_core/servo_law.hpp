#pragma once
/// @file servo_law.hpp
/// The control law: inputs of one cycle in, motor torques and coupling wrench out. Pure
/// computation on fixed-size Eigen types: no clock (`now`/`dt` arrive in the inputs), no I/O,
/// no allocation. docs/control.md explains the law, the gains and the safety layers.
///
/// Per cycle: forward kinematics, Jacobian and handle twist; gravity compensation (always when
/// powered); the client's command (NONE, IMPEDANCE wrench, or VIRTMECH spring-damper coupling to
/// the virtual object, with gains from the measured coupling loop, stiffer along a contact the
/// client reports, extrapolation over the sample's true age and a fade on silence); saturation
/// that keeps the damper; engagement ramp with a re-anchored spring, viscous hold and speed
/// brake; the channel's two-port passivity controller; the passivity guard on the handle port;
/// rate limit; workspace and soft joint-limit walls; joint torque saturation. The degraded SERVO
/// runs the same law (`degraded` is reported, not treated apart): a missed cycle keeps rendering
/// the coupling from the last sample, extrapolated and faded as it ages.

#include <array>
#include <cstdint>
#include <optional>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/arm_dynamics.hpp"
#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/rt_core/client_sample.hpp"
#include "hapticctrl/rt_core/joint_law.hpp"
#include "hapticctrl/rt_core/logical_state.hpp"
#include "hapticctrl/rt_core/servo_io.hpp"

namespace hapticctrl::rt_core {

struct LawConfig {
  /// No new sample for this long: flagged stale.
  Duration stale_after = std::chrono::milliseconds(5);
  /// A contact not refreshed for this long fades out over the next contact_fade (as the link).
  Duration contact_fresh = std::chrono::milliseconds(30);
  Duration contact_fade = std::chrono::milliseconds(15);
  /// The coupling along a contact is at most this share of the contact's stiffness: the loop
  /// through the object and back (its surface, the spring, the delay) keeps a gain below 1 at
  /// any delay (small gain, docs/control.md).
  double contact_share = 0.5;
  /// A reported surface is rendered at most as stiff as the device and this share of the
  /// sampled-data bound 2 B / T (B the device's stable damping, T the period; Colgate &
  /// Schenkel): 2000 N/m at 1 ms and at 10 ms.
  double surface_bound_share = 0.5;
  /// After a full disengagement the spring restarts relaxed where the handle is and regains its
  /// stretch at these speeds at most (re-anchoring, J1): the handle is never snapped back.
  double restretch_speed = 0.08;         ///< m/s
  double restretch_angular_speed = 0.5;  ///< rad/s
  /// While the hidden stretch returns, the handle's motion along it is damped with the device's
  /// stable damping (ServoLaw::restretch_damping), fading over the hidden stretch's last
  /// restretch_damper_fade (and restretch_damper_angular_fade).
  double restretch_damper_fade = 1e-3;          ///< m
  double restretch_damper_angular_fade = 0.01;  ///< rad

  Duration extrapolate_max = std::chrono::milliseconds(50);  ///< extrapolation horizon (sample age)
  /// Without a new sample the coupling force is zero by fade_after + fade_duration (45 ms; H1:
  /// 50 ms) and fades no faster than the device's peaks over fade_duration (1 N/ms), and over
  /// shortest_fade at least: a peak force from fade_after on, a smaller one later
  /// (ServoLaw::fade_of).
  Duration fade_after = std::chrono::milliseconds(10);
  Duration fade_duration = std::chrono::milliseconds(35);
  Duration shortest_fade = std::chrono::milliseconds(15);
  double release_rate = 1000.0;  ///< N/s: force change limit while fading, braking or released
  /// Every re-engagement (fresh data after a fade, the end of a brake, a new session, power-on)
  /// gives the handle its coupling back through a ramp this long. The spring restarts relaxed
  /// (re-anchoring), so the ramp only smooths the damper's return: 150 ms until 2026-12-03
  /// (before re-anchoring, a handle that drifted during a 300 ms blackout fell back at 0.16 m/s
  /// with 50 ms).
  Duration engage_duration = std::chrono::milliseconds(50);
  /// The viscous hold of a disengaged coupling lets go over this, and the coupling's damper
  /// comes back with it (J1: within 50 ms, without a step).
  Duration hold_release = std::chrono::milliseconds(50);
  /// Braking this long: kVelocityLimit.
  Duration overspeed_fault_after = std::chrono::milliseconds(250);
  double brake_release_ratio = 0.8;  ///< the brake lets go below this share of max_speed
  /// Loop delay assumed for a client that does not echo answers (protocol 1.0).
  Duration assumed_loop_delay = std::chrono::milliseconds(5);
  double joint_damping = 0.02;   ///< N·m·s/rad, always when powered (degraded too)
  double wall_margin = 0.05;     ///< rad before a joint limit where the soft wall starts
  double wall_stiffness = 20.0;  ///< N·m/rad
  bool passivity_guard = true;
  /// The joint-space commands (J6); their set points keep wall_margin from each joint's limit.
  JointLawConfig joint_space{};
  double default_object_mass = 0.5;  ///< kg, when the client declares none
  double default_time_step = 1e-3;   ///< s, when the client declares none
};

/// The handle's travel (the time integral of its twist, base frame) in 4 ms slots over the last
/// 512 ms: an IMPEDANCE client bills the work of its wrench on the handle's motion a whole loop
/// after that motion, so the core credits what it will bill for the last loop at its current
/// wrench (ServoLaw::guard_impedance; docs/control.md).
struct TravelHistory {
  static constexpr std::size_t kSlots = 128;
  static constexpr Duration kSlot = std::chrono::milliseconds(4);
  std::array<Vector6d, kSlots> travel{};
  Vector6d now_travel = Vector6d::Zero();
  std::int64_t newest = -1;  ///< the newest slot written (now / kSlot); -1: none
  std::int64_t first = -1;   ///< the first slot written
  /// Adds `twist` * `dt` to the travel and notes it at `now`. Safe in the cycle.
  HAPTICCTRL_RT void advance(TimePoint now, const Vector6d& twist, double dt) noexcept;
  /// The travel since `ago` before `now` (since the first note if that is older).
  [[nodiscard]] HAPTICCTRL_RT Vector6d since(TimePoint now, Duration ago) const noexcept;
};

/// What the law carries from one cycle to the next about the wrench it rendered. The main and
/// the degraded SERVO each run a law of their own; the task that commits a cycle hands this on
/// to both (ServoShared), so that the rate limit and the passivity observer continue from what
/// the handle actually got, whichever SERVO rendered it. (Each law keeping its own let the
/// wrench jump between the two laws' last values when degraded cycles interleaved: 17.8 N in one
/// 4 ms cycle against an 8 N limit, found by the fault-injection test, 2026-12-01.)
struct RenderMemory {
  Vector6d wrench = Vector6d::Zero();       ///< rate-limited handle wrench of last cycle
  Vector6d port_wrench = Vector6d::Zero();  ///< rendered at the port (with the guard's damping)
  double observed_energy = 0.0;             ///< J, see observed_energy()
  double engage = 0.0;                      ///< see ServoOutputs::engage
  Duration overspeed{0};                    ///< how long the handle has been over the limit
  bool braking = false;
  std::uint64_t session_id = 0;       ///< the session the coupling is engaged with
  Duration loop_delay{0};             ///< envelope of the measured loop delay
  Duration design_delay{0};           ///< loop delay the gains are designed for (in a band)
  CouplingGains gains;                ///< gains rendered last cycle (they slew to the design)
  double channel_in = 0.0;            ///< J the coupling put into the channel
  double channel_out = 0.0;           ///< J the channel gave the coupling
  Vector6d drift = Vector6d::Zero();  ///< the channel PC's shift of the object image
  TravelHistory travel;               ///< the handle's recent travel (IMPEDANCE)
  /// Re-anchoring: while `anchored`, the handle's spring renders the true stretch less `stretch`
  /// (linear, rotation vector: what it was at the re-engagement), which shrinks at a bounded
  /// speed and never exceeds the true stretch along its own direction.
  bool anchored = false;
  Vector6d stretch = Vector6d::Zero();
  /// A reported surface rendered at the servo rate (J1 for IMPEDANCE, J2 for VIRTMECH), while
  /// `on`: the plane as rendered last cycle (through `point`, along `normal`, base frame), which
  /// a model update never moves toward the handle; what the report is deeper than that plane is
  /// `hidden` (m), given back only from `budget` (J), the energy the surface's damper and
  /// friction dissipated; and where the handle sticks to it (the friction proxy).
  struct SurfaceMemory {
    bool on = false;
    double hidden = 0.0;
    Vector3d point = Vector3d::Zero();
    Vector3d normal = Vector3d::Zero();
    double budget = 0.0;
    Vector3d friction_anchor = Vector3d::Zero();
  };
  /// Every surface in force is rendered at once, each in a slot of its own that follows it from
  /// cycle to cycle by its normal (a peg on the floor of its hole and against its wall: rendering
  /// the deepest alone dropped the floor when the wall became the deeper, J3 2026-12-07).
  static constexpr std::size_t kSurfaces = 3;
  std::array<SurfaceMemory, kSurfaces> surfaces{};
  double surface_withheld = 0.0;  ///< J this session (ServoOutputs::surface_withheld)
  /// The contact the coupling rendered last on a fresh link, wholly engaged: rendered for the
  /// handle while the link is silent (ServoLaw::held_contact_force), as the surface the hand
  /// last felt (J1: without it a hand pushing 5 N into a 3000 N/m wall went 30 cm through it in
  /// a 2 s blackout). A plane the handle's point presses on, unilateral, in the base frame; the
  /// stiffnesses already scaled by the client's force factor; both 0: nothing held.
  struct HeldContact {
    Vector3d normal = Vector3d::Zero();  ///< the direction it pushes the handle
    Vector3d point = Vector3d::Zero();   ///< on the plane
    double coupling_stiffness = 0.0;     ///< N/m: the coupling's own (it fades with the link)
    double contact_stiffness = 0.0;      ///< N/m: the contact's (it fades with its reports)
    /// How deep `position` is behind the plane (> 0: pressing on it). Safe in the cycle.
    [[nodiscard]] HAPTICCTRL_RT double depth_at(const Vector3d& position) const noexcept {
      return (point - position).dot(normal);
    }
  };
  HeldContact held;
  static constexpr std::size_t kLoopSamples = 15;
  std::array<Duration, kLoopSamples> loop_samples{};  ///< the newest measured loops (median)
  std::uint64_t loop_next = 0;
  JointMemory joints;  ///< the joint-space commands' (joint_law.hpp)
};

/// Counters of the law (cycle-safe reads).
struct LawCounters {
  std::uint64_t non_finite_outputs = 0;
  std::uint64_t speed_limited = 0;
  std::uint64_t passivity_active = 0;
  std::uint64_t rate_limited = 0;
  std::uint64_t workspace_walls = 0;    ///< cycles with the handle outside the workspace box
  std::uint64_t channel_pc_active = 0;  ///< cycles the two-port passivity controller acted
  std::uint64_t channel_force_cut = 0;  ///< of those, cycles it also cut the coupling's force
  std::uint64_t reanchored = 0;         ///< re-engagements that restarted the spring relaxed
  /// Cycles in which a surface's report came toward the handle and the rendered plane stayed
  /// (a passive model update, ServoLaw::render_surface).
  std::uint64_t surface_updates_held = 0;
  /// Cycles in which the joint-space passivity guard damped a joint (ARTICULAR_IMPEDANCE).
  std::uint64_t joint_passivity_active = 0;
};

class ServoLaw {
 public:
  ServoLaw(const ArmDynamics& dynamics, const LawConfig& config = {}) noexcept;

  /// Real-time contract: noexcept, no allocation; safe in the cycle.
  HAPTICCTRL_RT void compute(const ServoInputs& in, bool degraded, ServoOutputs& out) noexcept;

  /// Gains the controller derives from the object's mass/inertia, the client's time step and
  /// the coupling loop's delay (s), bounded by the device (model limits), then overridden
  /// (within the same bounds) by the client's non-zero overrides. Real-time contract: safe in
  /// the cycle.
  [[nodiscard]] HAPTICCTRL_RT CouplingGains derive_gains(const ClientSample& client,
                                                         double loop_delay) const noexcept;

  /// Net energy the user has given the rendering port at the handle (J): negative means the port
  /// delivered more energy to the hand than it received (the guard then adds damping).
  [[nodiscard]] double observed_energy() const noexcept { return memory_.observed_energy; }
  /// Continues from what was rendered last (the committed cycle's memory). Safe in the cycle.
  HAPTICCTRL_RT void continue_from(const RenderMemory& memory) noexcept { memory_ = memory; }
  /// What this law rendered in its last compute(). Safe in the cycle.
  [[nodiscard]] HAPTICCTRL_RT const RenderMemory& memory() const noexcept { return memory_; }
  [[nodiscard]] const LawCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] const LawConfig& config() const noexcept { return config_; }
  [[nodiscard]] HAPTICCTRL_RT const ArmDynamics& dynamics() const noexcept { return *dynamics_; }

 private:
  /// The coupling's spring and damper parts (base frame), before limits: on the handle, and
  /// opposite on the object (`object_spring`, `object_damper`: the same but where a surface the
  /// client reports is rendered here in the handle's place).
  struct Coupling {
    Vector6d spring = Vector6d::Zero();
    Vector6d damper = Vector6d::Zero();
    Vector6d object_spring = Vector6d::Zero();
    Vector6d object_damper = Vector6d::Zero();
    Vector6d stretch = Vector6d::Zero();  ///< the stretch the handle's spring renders
    /// Rendered here and outside the two-port: a surface the client reports.
    Vector6d local = Vector6d::Zero();
    /// The contact in force as the handle feels it (hold_contact); none: no contact touching.
    RenderMemory::HeldContact contact;
    bool contact_in_force = false;
    bool contact_whole = false;  ///< fresh (its weight 1): what the hand feels is all of it
    bool contact_local = false;  ///< the contact is a surface rendered here, not the coupling
  };
  /// A surface the client reports, as rendered at the servo rate for the handle's point (base
  /// frame, client force units: the force factor is applied with the client's wrench).
  struct Surface {
    Vector3d normal = Vector3d::Zero();    ///< out of the surface
    double share = 0.0;                    ///< fresh and touching: 0..1
    double weight = 0.0;                   ///< fresh: 0..1 (contact_fresh, contact_fade)
    double depth = 0.0;                    ///< of the handle's point, > 0 inside
    Vector3d point = Vector3d::Zero();     ///< where the handle's point meets it
    double force = 0.0;                    ///< along the normal, >= 0 (render_surface)
    Vector3d friction = Vector3d::Zero();  ///< in the surface's plane (render_surface)
    double friction_static = 0.0;
    double friction_dynamic = 0.0;
    double stiffness = 0.0;  ///< N/m, base metres
    double damping = 0.0;    ///< N.s/m
    /// The memory slot that follows it (render_surfaces gives every surface found one);
    /// kSurfaces: none yet.
    std::size_t slot = RenderMemory::kSurfaces;
    /// Fresh, touching and with the handle's point inside: rendered (render_surface). Safe in
    /// the cycle.
    [[nodiscard]] HAPTICCTRL_RT bool pressed() const noexcept { return share > 0.0 && depth > 0.0; }
  };
  /// The surfaces the client reports, one per direction (contacts whose normals agree within
  /// kSameSurface are one plane, the deepest of them), the deepest kSurfaces of them first.
  struct Surfaces {
    std::array<Surface, RenderMemory::kSurfaces> list{};
    std::size_t count = 0;
    std::uint32_t fresh = 0;
    std::optional<Duration> age;  ///< of the newest fresh contact (our clock); none: no contact
    std::size_t strongest = 0;    ///< the one that pushes most (the deepest when none pushes)
    Vector3d push = Vector3d::Zero();  ///< all of them together: their forces and friction
    double in_force = 0.0;  ///< the largest share of a surface in force (over its first 0.5 mm)
  };
  /// Where the client's object is now, as the coupling sees it (base frame).
  struct ObjectImage {
    Vector3d position = Vector3d::Zero();
    Vector3d ahead = Vector3d::Zero();  ///< the extrapolation over the sample's age (in position)
    Matrix3d rotation = Matrix3d::Identity();
    Vector6d twist = Vector6d::Zero();
  };
  /// The stiffening along the dominant contact (base frame).
  struct Stiffening {
    Vector3d normal = Vector3d::Zero();
    double share = 0.0;      ///< how much of the contact is in force (fresh, touching): 0..1
    double weight = 0.0;     ///< how fresh it is: 0..1 (contact_fresh, contact_fade)
    double stiffness = 0.0;  ///< added to the handle's coupling (its share not replaced)
    double damping = 0.0;
    /// Added to the object's, on the handle's depth in the surface (the stretch along the normal
    /// plus the object's penetration): with the coupling's own, the surface's stiffness, so that
    /// the object is pressed into its surface with the force the hand feels (J2).
    double object_stiffness = 0.0;
    double penetration = 0.0;  ///< the object's into its surface now (m, base)
    std::uint32_t fresh = 0;
  };
  /// Every output of the cycle set to its value before the coupling is rendered (none of it).
  HAPTICCTRL_RT void start_outputs(const ServoInputs& in, const Vector6d& q,
                                   ServoOutputs& out) const noexcept;
  /// Adds to `target` the speed brake, or the viscous hold of a session whose coupling is not
  /// wholly engaged.
  HAPTICCTRL_RT void brake_or_hold(const ServoInputs& in, const ServoOutputs& out,
                                   const Vector6d& twist, double damper_share,
                                   Vector6d& target) noexcept;
  /// The joint torques: gravity, joint damping and walls, the handle's wrench (as joint torques)
  /// and the joint command, each joint clamped to its peak; none if not finite.
  HAPTICCTRL_RT void command_torques(const ServoInputs& in, const Vector6d& handle_torque,
                                     const Vector6d& joint_command, ServoOutputs& out) noexcept;
  HAPTICCTRL_RT Coupling client_wrench(const ServoInputs& in, const ClientFrame& frame,
                                       const ChainState& chain, const Vector6d& twist,
                                       ServoOutputs& out) noexcept;
  HAPTICCTRL_RT ObjectImage object_image(const ServoInputs& in,
                                         const ClientFrame& frame) const noexcept;
  /// `reported`: the object's position as the client reported it (base frame, not extrapolated).
  [[nodiscard]] HAPTICCTRL_RT Stiffening contact_stiffening(const ServoInputs& in,
                                                            const ClientFrame& frame,
                                                            const Vector3d& reported,
                                                            const CouplingGains& g) const noexcept;
  /// The fresh surfaces the client reports, for the handle's point: an IMPEDANCE client's
  /// contact is where its handle's point meets the surface; a VIRTMECH client's (`on_object`) is
  /// on its object, which the coupling holds at the handle, so the handle's point is the
  /// handle's position offset as the contact point was from the object.
  [[nodiscard]] HAPTICCTRL_RT Surfaces reported_surfaces(const ServoInputs& in,
                                                         const ClientFrame& frame,
                                                         const ChainState& chain,
                                                         bool on_object) const noexcept;
  /// Adds `s` to the surfaces found: merged into the one it shares its normal with (the deeper
  /// stays), or added, or in place of the shallowest when they are full and it is deeper.
  HAPTICCTRL_RT static void add_surface(Surfaces& found, const Surface& s) noexcept;
  /// Gives every surface found the memory slot that follows it (forgetting the slots no surface
  /// continues), bounds their stiffness together (the sum, by 2 B / T) and renders those
  /// pressed; a surface not pressed is remembered where it is reported.
  HAPTICCTRL_RT void render_surfaces(Surfaces& surfaces, const ChainState& chain,
                                     const Vector6d& twist, double dt) noexcept;
  HAPTICCTRL_RT void render_surface(Surface& surface, RenderMemory::SurfaceMemory& m,
                                    const ChainState& chain, const Vector6d& twist,
                                    double dt) noexcept;
  /// The reported surfaces rendered for the handle, the strongest noted in `coupling` as its
  /// contact.
  HAPTICCTRL_RT Surfaces local_surfaces(const ServoInputs& in, const ClientFrame& frame,
                                        const ChainState& chain, const Vector6d& twist,
                                        bool on_object, Coupling& coupling,
                                        ServoOutputs& out) noexcept;
  /// Notes the contact in force while the link is fresh and the coupling whole (or forgets it
  /// when none is), for held_contact_force.
  HAPTICCTRL_RT void hold_contact(const ServoInputs& in, const Coupling& coupling,
                                  double engage) noexcept;
  /// The held contact's push on the handle: the share of it the link's coupling no longer
  /// renders (what faded with the link), on the handle's position now.
  [[nodiscard]] HAPTICCTRL_RT Vector3d held_contact_force(const ServoInputs& in,
                                                          double engage) const noexcept;
  HAPTICCTRL_RT Vector6d stretch_in_use(const Vector6d& stretch, const Vector6d& twist,
                                        double dt) noexcept;
  [[nodiscard]] HAPTICCTRL_RT Vector6d restretch_damping(const Vector6d& twist) const noexcept;
  HAPTICCTRL_RT void track_loop_delay(const ServoInputs& in) noexcept;
  HAPTICCTRL_RT CouplingGains slew_gains(const CouplingGains& target, Duration dt) noexcept;
  [[nodiscard]] HAPTICCTRL_RT double fade_of(Duration silence, double peak_share) const noexcept;
  [[nodiscard]] HAPTICCTRL_RT double peak_share(const Vector6d& wrench) const noexcept;
  [[nodiscard]] HAPTICCTRL_RT Vector6d joint_space(const ServoInputs& in, double engage,
                                                   double rate, double dt,
                                                   ServoOutputs& out) noexcept;
  HAPTICCTRL_RT void follow_session(const ServoInputs& in) noexcept;
  HAPTICCTRL_RT Vector6d guard_channel(const ServoInputs& in, const ClientFrame& frame,
                                       const Vector6d& coupling, const Vector6d& to_object,
                                       const Vector6d& stretch, double dt) noexcept;
  HAPTICCTRL_RT Vector6d guard_impedance(const ServoInputs& in, const ClientFrame& frame,
                                         const Vector6d& handle_force, const Vector6d& twist,
                                         double dt) noexcept;
  /// Books one period's channel power at the core's end (>= 0: in) and returns the excess of
  /// the energy out over `budget`, the client's reported energy in.
  HAPTICCTRL_RT double book_channel_power(double power, double budget, double dt) noexcept;
  HAPTICCTRL_RT double update_engagement(const ServoInputs& in, const Vector6d& twist, double fade,
                                         ServoOutputs& out) noexcept;
  HAPTICCTRL_RT void set_limits(const ClientSample& client, ServoOutputs& out) const noexcept;
  HAPTICCTRL_RT Vector6d rate_limit(const Vector6d& target, double rate, double dt) noexcept;
  HAPTICCTRL_RT Vector6d guard_passivity(const Vector6d& wrench, const Vector6d& twist,
                                         double dt) noexcept;
  HAPTICCTRL_RT Vector6d joint_walls(const Vector6d& q) const noexcept;
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t joint_bounds(const Vector6d& q) const noexcept;
  HAPTICCTRL_RT Vector6d workspace_wall(const Vector3d& velocity) noexcept;
  HAPTICCTRL_RT void express_for_client(const ClientFrame& frame, const Vector6d& twist,
                                        ServoOutputs& out) const noexcept;
  /// Whether the client reports its channel energy with an IMPEDANCE wrench (protocol 1.3): the
  /// two-port covers it instead of the one-port guard.
  [[nodiscard]] HAPTICCTRL_RT static bool two_port_impedance(const ServoInputs& in) noexcept;

  const ArmDynamics* dynamics_;
  LawConfig config_;
  JointLaw joints_;
  ChainState chain_;
  RenderMemory memory_;
  LawCounters counters_;
};

}  // namespace hapticctrl::rt_core
