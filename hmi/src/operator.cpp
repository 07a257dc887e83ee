// Implements operator.hpp: the operator's hands on one running controller: ctrl commands (power,
// emergency stop, stop) and the operator wrench on the simulated handle, written through the
// `force` region at a bounded rate.
#include "hapticctrl/hmi/operator.hpp"
#include "hapticctrl/base/time.hpp"

#include <algorithm>
#include <thread>

#include "hapticctrl/hmi/hand_motion.hpp"
#include "hapticctrl/shm/rendezvous.hpp"

namespace hapticctrl::hmi {
namespace {

using namespace std::chrono_literals;

/// How often settle_force() and send_and_wait() look again.
constexpr auto kPoll = 2ms;
/// Longest time step one tick() applies to the force ramp (s).
constexpr double kMaxTickStep = 0.02;

std::string no_controller_message(const std::string& instance, const std::string& detail) {
  std::string text = detail;
  const std::vector<std::string> running = shm::listed_instances();
  if (running.empty()) {
    text += "; no controller runs on this machine (start one: hapticctrl-core --instance " +
            instance + ")";
  } else {
    text += "; instances found:";
    for (const auto& name : running) {
      text += " " + name;
    }
    text += " (choose one with --instance NAME)";
  }
  return text;
}

shm::Segment attach_segment(const std::string& instance, bool with_force) {
  shm::AttachOptions options;
  options.ctrl_writer = true;
  if (with_force) {
    options.write.push_back(shm::RegionId::kForce);
  }
  return shm::Segment::attach(instance, options);
}

}  // namespace

Operator::Operator(const std::string& instance, bool want_force) {
  try {
    try {
      segment_.emplace(attach_segment(instance, want_force));
    } catch (const shm::ShmError& e) {
      if (!want_force || e.code() != shm::ShmErrc::kWriterConflict ||
          e.region() != shm::RegionId::kForce) {
        throw;
      }
      force_unavailable_ = e.what();
      segment_.emplace(attach_segment(instance, false));
    }
  } catch (const shm::ShmError& e) {
    if (e.code() == shm::ShmErrc::kNoController || e.code() == shm::ShmErrc::kBadInstanceName) {
      throw HmiError(no_controller_message(instance, e.what()));
    }
    throw HmiError(e.what());
  }
  if (!want_force) {
    force_unavailable_ = "this command does not write the operator force";
  }
  if (force_available()) {
    // Start from what the handle feels now: a new panel must not make the force jump (nor
    // drop a hand a killed player left gripping).
    shm::ForcePayload current;
    if (segment_->region<shm::RegionId::kForce>().read(current).ok() &&
        slew_.acceptable(current.wrench) && shm::hand_acceptable(current.hand)) {
      slew_ = shm::ForceSlew(shm::ForceLimits{}, current.wrench);
      hand_ = current.hand;
    }
  }
}

void Operator::send(shm::CtrlCode code) {
  const auto deadline = hapticctrl::MonotonicClock::now() + 100ms;
  while (segment_->ctrl_writer().send(code, 0, to_ns(MonotonicClock::now())) !=
         shm::CtrlSendStatus::kQueued) {
    if (hapticctrl::MonotonicClock::now() >= deadline) {
      throw HmiError("the controller's command queue stays full: is hapticctrl-core stalled?");
    }
    std::this_thread::sleep_for(kPoll);
  }
}

bool Operator::send_and_wait(shm::CtrlCode code,
                             const std::function<bool(const ControllerStatus&)>& done,
                             std::chrono::milliseconds timeout) {
  send(code);
  const auto deadline = hapticctrl::MonotonicClock::now() + timeout;
  while (hapticctrl::MonotonicClock::now() < deadline) {
    if (done(status())) {
      return true;
    }
    std::this_thread::sleep_for(kPoll);
  }
  return done(status());
}

bool Operator::request_force(const shm::Vector6& wrench) {
  return force_available() && slew_.set_target(wrench);
}

void Operator::tick(TimePoint now) {
  // A caller that paused (a stalled terminal) resumes with one bounded step, not a jump.
  const double dt =
      last_tick_ == kNotYet ? 0.0 : std::min(to_seconds(now - last_tick_), kMaxTickStep);
  last_tick_ = now;
  const bool moved = force_available() && slew_.step(dt);
  if (moved || (force_available() && hand_changed_)) {
    segment_->writable<shm::RegionId::kForce>().publish_quietly(
        shm::ForcePayload{slew_.applied(), hand_}, to_ns(now));
    hand_changed_ = false;
  }
}

void Operator::release_hand() {
  if (!force_available() || (hand_.stiffness == 0.0 && hand_.damping == 0.0 &&
                             hand_.angular_stiffness == 0.0 && hand_.angular_damping == 0.0)) {
    return;
  }
  const shm::HandGrip held = hand_;
  const TimePoint start = MonotonicClock::now();
  const TimePoint end = start + from_seconds(HandMotion::kGripRamp);
  for (TimePoint now = start; now < end; now = MonotonicClock::now()) {
    const double grip = 1.0 - to_seconds(now - start) / HandMotion::kGripRamp;
    shm::HandGrip g = held;
    g.anchor_velocity = {};
    g.stiffness *= grip;
    g.damping *= grip;
    g.angular_stiffness *= grip;
    g.angular_damping *= grip;
    (void)set_hand(g);  // within the held grip's range
    tick(MonotonicClock::now());
    std::this_thread::sleep_for(kPoll);
  }
  (void)set_hand({});
  tick(MonotonicClock::now());
}

bool Operator::set_hand(const shm::HandGrip& hand) {
  if (!force_available() || !shm::hand_acceptable(hand)) {
    return false;
  }
  hand_ = hand;
  hand_changed_ = true;
  return true;
}

void Operator::settle_force() {
  // Bounded: the rate limit sets the time; 2 s more covers any scheduling delay.
  const auto deadline = hapticctrl::MonotonicClock::now() +
                        std::chrono::duration<double>(slew_.time_to_settle()) + 2s;
  tick(MonotonicClock::now());
  while (!slew_.settled() && hapticctrl::MonotonicClock::now() < deadline) {
    std::this_thread::sleep_for(kPoll);
    tick(MonotonicClock::now());
  }
}

ControllerStatus Operator::status() const {
  return read_status(*segment_, MonotonicClock::now());
}

bool Operator::controller_alive() const {
  return segment_->still_current();  // the core runs and has not stopped
}

}  // namespace hapticctrl::hmi
