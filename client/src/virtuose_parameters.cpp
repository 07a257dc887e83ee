// The C API's parameters, virtual object and power: each setter is a reliable exchange with the
// controller, and what it acknowledged is what the getters return.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/protocol/values.hpp"
#include "virtuose_context.hpp"

using hapticctrl::client::CommandType;
using hapticctrl::client::Connection;
using hapticctrl::client::StateSnapshot;
using hapticctrl::client::virtuose::AttachedObject;
using hapticctrl::client::virtuose::Context;
using hapticctrl::client::virtuose::context_of;
using hapticctrl::client::virtuose::fail;
using hapticctrl::client::virtuose::Settings;
using hapticctrl::client::virtuose::to_doubles;

namespace {

/// How long a setter waits for its effect in the controller's answers.
constexpr auto kEffectTimeout = std::chrono::milliseconds(500);

/// Runs a parameter setter's call; on success records what the controller acknowledged.
template <typename Call, typename Record>
int set_and_record(VirtContext vc, Call&& call, Record&& record) noexcept {
  Context* c = context_of(vc);
  if (c == nullptr) {
    return -1;
  }
  const int rc = c->guarded(std::forward<Call>(call));
  if (rc == 0) {
    const std::lock_guard lock(c->mutex);
    record(c->settings);
  }
  return rc;
}

/// Copies one acknowledged setting out, for a getter.
template <typename Read>
int get_setting(VirtContext vc, const void* out, const char* what, Read&& read) noexcept {
  Context* c = context_of(vc, out, what);
  if (c == nullptr) {
    return -1;
  }
  const std::lock_guard lock(c->mutex);
  read(c->settings);
  return 0;
}

Context& live(VirtContext vc) noexcept {
  return *static_cast<Context*>(vc);  // only after context_of said it is live
}

/// The smallest of three gains of a {rotation x3, translation x3} array, from `first`.
double smallest_of_three(const float* gains, int first) noexcept {
  return static_cast<double>(std::min({gains[first], gains[first + 1], gains[first + 2]}));
}

/// VirtuoseAPI's {rotation x3, translation x3} order of the gains in force.
int write_gains(VirtContext vc, float* out, const char* what, bool damping) noexcept {
  Context* c = context_of(vc, out, what);
  if (c == nullptr) {
    return -1;
  }
  const auto g = c->link()->statistics().coupling_gains;  // k_lin b_lin k_ang b_ang
  const auto rotation = static_cast<float>(damping ? g[3] : g[2]);
  const auto translation = static_cast<float>(damping ? g[1] : g[0]);
  std::fill_n(out, 3, rotation);
  std::fill_n(out + 3, 3, translation);
  return 0;
}

}  // namespace

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

int virtSetTimeStep(VirtContext VC, float step) {
  return set_and_record(
      VC, [&] { live(VC).link()->set_time_step(static_cast<double>(step)); },
      [&](Settings& s) { s.time_step = step; });
}

int virtGetTimeStep(VirtContext VC, float* step) {
  return get_setting(VC, step, "virtGetTimeStep: NULL output",
                     [&](const Settings& s) { *step = s.time_step; });
}

int virtSetIndexingMode(VirtContext VC, VirtIndexingType indexing_mode) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  return set_and_record(
      VC,
      [&] {
        vc->link()->set_indexing_mode(static_cast<hapticctrl::client::IndexingMode>(indexing_mode));
      },
      [&](Settings& s) {
        s.indexing = indexing_mode;
        vc->indexing.set_mode(static_cast<std::uint32_t>(indexing_mode));
      });
}

int virtGetIndexingMode(VirtContext VC, VirtIndexingType* indexing_mode) {
  return get_setting(VC, indexing_mode, "virtGetIndexingMode: NULL output",
                     [&](const Settings& s) { *indexing_mode = s.indexing; });
}

int virtSetForceFactor(VirtContext VC, float force_factor) {
  return set_and_record(
      VC, [&] { live(VC).link()->set_force_factor(static_cast<double>(force_factor)); },
      [&](Settings& s) { s.force_factor = force_factor; });
}

int virtGetForceFactor(VirtContext VC, float* force_factor) {
  return get_setting(VC, force_factor, "virtGetForceFactor: NULL output",
                     [&](const Settings& s) { *force_factor = s.force_factor; });
}

int virtSetSpeedFactor(VirtContext VC, float speed_factor) {
  return set_and_record(
      VC, [&] { live(VC).link()->set_speed_factor(static_cast<double>(speed_factor)); },
      [&](Settings& s) { s.speed_factor = speed_factor; });
}

int virtGetSpeedFactor(VirtContext VC, float* speed_factor) {
  return get_setting(VC, speed_factor, "virtGetSpeedFactor: NULL output",
                     [&](const Settings& s) { *speed_factor = s.speed_factor; });
}

int virtSetBaseFrame(VirtContext VC, float* base) {
  if (context_of(VC, base, "virtSetBaseFrame: NULL pose") == nullptr) {
    return -1;
  }
  return set_and_record(
      VC, [&] { live(VC).link()->set_base_frame(to_doubles<7>(base)); },
      [&](Settings& s) { std::copy_n(base, 7, s.base_frame.begin()); });
}

int virtGetBaseFrame(VirtContext VC, float* base) {
  return get_setting(VC, base, "virtGetBaseFrame: NULL output", [&](const Settings& s) {
    std::copy(s.base_frame.begin(), s.base_frame.end(), base);
  });
}

int virtSetObservationFrame(VirtContext VC, float* obs) {
  if (context_of(VC, obs, "virtSetObservationFrame: NULL pose") == nullptr) {
    return -1;
  }
  return set_and_record(
      VC, [&] { live(VC).link()->set_observation_frame(to_doubles<7>(obs)); },
      [&](Settings& s) { std::copy_n(obs, 7, s.observation_frame.begin()); });
}

int virtGetObservationFrame(VirtContext VC, float* obs) {
  return get_setting(VC, obs, "virtGetObservationFrame: NULL output", [&](const Settings& s) {
    std::copy(s.observation_frame.begin(), s.observation_frame.end(), obs);
  });
}

int virtSetCommandType(VirtContext VC, VirtCommandType type) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  CommandType t = CommandType::kNone;
  switch (type) {
    case COMMAND_TYPE_NONE:
      break;
    case COMMAND_TYPE_IMPEDANCE:
      t = CommandType::kImpedance;
      break;
    case COMMAND_TYPE_VIRTMECH:
      t = CommandType::kVirtmech;
      break;
    case COMMAND_TYPE_ARTICULAR:
      t = CommandType::kArticular;
      break;
    case COMMAND_TYPE_ARTICULAR_IMPEDANCE:
      t = CommandType::kArticularImpedance;
      break;
    default:
      return fail(VC, VIRT_E_MODE_NOT_SUPPORTED,
                  "virtSetCommandType: hapticctrl's controller has COMMAND_TYPE_NONE, "
                  "IMPEDANCE, VIRTMECH, ARTICULAR and ARTICULAR_IMPEDANCE");
  }
  if ((t == CommandType::kArticular || t == CommandType::kArticularImpedance) &&
      (vc->link()->features() & HCP_FEATURE_JOINT_CONTROL) == 0) {
    return fail(VC, VIRT_E_MODE_NOT_SUPPORTED,
                "virtSetCommandType: the controller's protocol is older than 1.4, which brought "
                "the joint-space command types");
  }
  return set_and_record(
      VC, [&] { vc->link()->set_command_type(t); },
      [&](Settings& s) {
        s.command_type = type;
        vc->command_type = t;
      });
}

int virtGetCommandType(VirtContext VC, VirtCommandType* type) {
  return get_setting(VC, type, "virtGetCommandType: NULL output",
                     [&](const Settings& s) { *type = s.command_type; });
}

int virtSetTimeoutValue(VirtContext VC, float time_value) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  if (!std::isfinite(time_value) || time_value <= 0.0F) {
    return fail(VC, VIRT_E_INCORRECT_VALUE,
                "virtSetTimeoutValue: not a positive number of seconds");
  }
  // Haption's applications give the time after which a silent link counts as lost, often a few
  // milliseconds (3 ms in a public one, refused here until J6): outside the bridge's watchdog
  // range it is brought into it, and said (virtGetErrorDetail, with VIRT_E_NO_ERROR).
  const double asked_ms = static_cast<double>(time_value) * 1000.0;
  const auto ms = std::chrono::milliseconds(
      std::lround(std::clamp(asked_ms, static_cast<double>(hapticctrl::protocol::kMinWatchdogMs),
                             static_cast<double>(hapticctrl::protocol::kMaxWatchdogMs))));
  const int rc = set_and_record(
      VC, [&] { vc->link()->set_watchdog(ms); }, [&](Settings& s) { s.watchdog = ms; });
  if (rc == 0 && std::abs(asked_ms - static_cast<double>(ms.count())) >= 0.5) {
    std::array<char, 160> text{};
    std::snprintf(text.data(), text.size(),
                  "virtSetTimeoutValue: %.1f ms is outside the controller's %u-%u ms: %lld ms in "
                  "force",
                  asked_ms, hapticctrl::protocol::kMinWatchdogMs,
                  hapticctrl::protocol::kMaxWatchdogMs, static_cast<long long>(ms.count()));
    vc->error.set(VIRT_E_NO_ERROR, text.data());
  }
  return rc;
}

int virtGetTimeoutValue(VirtContext VC, float* time_value) {
  Context* vc = context_of(VC, time_value, "virtGetTimeoutValue: NULL output");
  if (vc == nullptr) {
    return -1;
  }
  // The watchdog in force: the bridge may have capped what was asked (--max-watchdog-ms).
  *time_value = static_cast<float>(vc->link()->watchdog_ms()) / 1000.0F;
  return 0;
}

int virtSaturateTorque(VirtContext VC, float forceThreshold, float momentThreshold) {
  const std::array<double, 2> limits{static_cast<double>(forceThreshold),
                                     static_cast<double>(momentThreshold)};
  return set_and_record(
      VC, [&] { live(VC).link()->set_force_limits(limits[0], limits[1]); },
      [&](Settings& s) { s.force_limits = limits; });
}

int virtAttachVO(VirtContext VC, float mass, float* mxmymz) {
  if (context_of(VC, mxmymz, "virtAttachVO: NULL inertia") == nullptr) {
    return -1;
  }
  const AttachedObject object{static_cast<double>(mass), to_doubles<3>(mxmymz)};
  return set_and_record(
      VC, [&] { live(VC).link()->attach_object(object.mass, object.inertia); },
      [&](Settings& s) { s.object = object; });
}

int virtAttachVOAvatar(VirtContext VC, float mass, float* mxmymz) {
  // The object is coupled to the avatar: the commands go through the indexing (flush_locked).
  return virtAttachVO(VC, mass, mxmymz);
}

int virtAttachQSVO(VirtContext VC, float* Ks, float* Bs) {
  if (context_of(VC, Ks, "virtAttachQSVO: NULL stiffness") == nullptr ||
      context_of(VC, Bs, "virtAttachQSVO: NULL damping") == nullptr) {
    return -1;
  }
  const std::array<double, 4> gains{smallest_of_three(Ks, 3), smallest_of_three(Bs, 3),
                                    smallest_of_three(Ks, 0), smallest_of_three(Bs, 0)};
  return set_and_record(
      VC,
      [&] {
        const std::shared_ptr<Connection> link = live(VC).link();
        link->set_gains(gains[0], gains[1], gains[2], gains[3]);
        link->attach_object(0.0, {0.0, 0.0, 0.0});  // quasi-static: no mass
      },
      [&](Settings& s) {
        s.gains = gains;
        s.object = AttachedObject{};
      });
}

int virtDetachVO(VirtContext VC) {
  return set_and_record(
      VC, [&] { live(VC).link()->detach_object(); }, [&](Settings& s) { s.object.reset(); });
}

int virtDetachVOAvatar(VirtContext VC) {
  return virtDetachVO(VC);
}

int virtGetSimulationStiffness(VirtContext VC, float* stiffness) {
  return write_gains(VC, stiffness, "virtGetSimulationStiffness: NULL output", false);
}

int virtGetSimulationDamping(VirtContext VC, float* damping) {
  return write_gains(VC, damping, "virtGetSimulationDamping: NULL output", true);
}

int virtSetPowerOn(VirtContext VC, int power) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  const bool on = power != 0;
  const std::shared_ptr<Connection> link = vc->link();
  if (set_and_record(
          VC, [&] { link->set_power(on); }, [&](Settings& s) { s.power = on; }) != 0) {
    return -1;
  }
  if (vc->loop_running.load()) {
    return 0;  // from the periodic function: the next answers show it (waiting would stall them)
  }
  // The acknowledgement says the bridge passed it on; return once the controller did it (a getter
  // then reports it), or say why not.
  using hapticctrl::MonotonicClock;
  StateSnapshot s = link->snapshot();
  const hapticctrl::TimePoint deadline = MonotonicClock::now() + kEffectTimeout;
  while (s.powered() != on) {
    if (on && s.emergency_stop()) {
      return fail(VC, VIRT_E_CONTROLLER_REFUSED,
                  "virtSetPowerOn: the emergency stop is latched (reset it first)");
    }
    const hapticctrl::Duration left = deadline - MonotonicClock::now();
    if (left <= hapticctrl::Duration::zero() || !link->wait_for_answer(s.cycle, left, s)) {
      return fail(VC, VIRT_E_TIME_OUT, "virtSetPowerOn: the controller did not switch the power");
    }
  }
  return 0;
}

int virtEnableForceFeedback(VirtContext VC, int enable) {
  Context* vc = context_of(VC);
  if (vc == nullptr) {
    return -1;
  }
  const std::lock_guard lock(vc->mutex);
  vc->force_feedback = enable != 0;
  if (vc->force_feedback || vc->loop_running.load()) {
    return 0;  // the next command carries it (the loop's is due within a period)
  }
  // Off at once: a silent application would keep the last frame's forces.
  vc->pose_pending = vc->command_type == CommandType::kVirtmech;
  vc->wrench_pending = vc->command_type == CommandType::kImpedance;
  vc->joints_pending = vc->command_type == CommandType::kArticularImpedance;
  return vc->flush_locked("virtEnableForceFeedback: the last command out of range");
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
