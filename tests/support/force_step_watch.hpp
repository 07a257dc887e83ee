#pragma once
// ForceStepWatch: follows a live core's every cycle from a thread and keeps the force steps it
// rendered beyond its limits (tests/e2e/fault_injection_test.cpp, shared_memory_abuse_test.cpp).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>

#include "hapticctrl/arm_model/arm_model.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace hapticctrl::test {

using namespace std::chrono_literals;

/// Follows every cycle of a core from a thread and keeps the largest change per cycle of the
/// force the motors put on the handle (coupling, norm) beyond what the law allows (the rate
/// limit, plus the passivity guard's damping, which only opposes the handle's motion and comes
/// after the rate limit: docs/control.md), the fastest change of the operator's
/// wrench between two of its samples (per axis, by their timestamps: its writer is an ordinary
/// process, paced by its own clock), and whether the core ever left its running state.
class ForceStepWatch {
 public:
  /// `period_s`: the core's cycle, s.
  ForceStepWatch(const shm::Segment& segment, const arm_model::ArmLimits& limits, double period_s)
      : segment_(segment),
        rate_step_(limits.force_rate * period_s),
        max_damping_(limits.max_damping_linear),
        thread_([this] { follow(); }) {}
  ForceStepWatch(const ForceStepWatch&) = delete;
  ForceStepWatch& operator=(const ForceStepWatch&) = delete;
  ~ForceStepWatch() { stop(); }

  void stop() {
    running_ = false;
    if (thread_.joinable()) {
      thread_.join();
    }
  }
  [[nodiscard]] double largest_coupling_step() const { return coupling_step_; }
  /// The largest amount by which a step exceeded what the law allows [N] (0 or less: none).
  [[nodiscard]] double largest_coupling_excess() const { return coupling_excess_; }
  [[nodiscard]] double fastest_operator_rate() const { return operator_rate_; }
  /// Timestamp of the newest operator force sample seen (CLOCK_MONOTONIC ns).
  [[nodiscard]] std::int64_t last_force_sample_ns() const { return last_force_ns_; }
  [[nodiscard]] bool left_running() const { return left_running_; }
  [[nodiscard]] std::uint64_t cycles() const { return cycles_; }

 private:
  void follow() {
    const auto& vp = segment_.region<shm::RegionId::kVp>();
    const auto& position = segment_.region<shm::RegionId::kPosition>();
    shm::PositionPayload last;
    bool have_last = false;
    while (running_) {
      vp.wait_for_publish(vp.sequence_word(), 50ms);
      // The header too: a core that fails safe stops publishing position before it says so.
      if (segment_.header().core_state.load() !=
          static_cast<std::uint32_t>(shm::CoreState::kRunning)) {
        left_running_ = true;
      }
      follow_operator_force();
      shm::PositionPayload p;
      if (!position.read(p).ok() || (have_last && p.cycle == last.cycle)) {
        continue;
      }
      if (p.core_state != static_cast<std::uint32_t>(shm::CoreState::kRunning)) {
        left_running_ = true;
      }
      const bool rendering = [](const shm::PositionPayload& x) {
        return x.core_state == static_cast<std::uint32_t>(shm::CoreState::kRunning) &&
               (x.state_word & shm::state_bits::kPowered) != 0;
      }(p);
      if (have_last && p.cycle > last.cycle && rendering && last_rendering_) {
        const auto gap = static_cast<double>(p.cycle - last.cycle);
        const double coupling = std::hypot(p.rendered_wrench[0] - last.rendered_wrench[0],
                                           p.rendered_wrench[1] - last.rendered_wrench[1],
                                           p.rendered_wrench[2] - last.rendered_wrench[2]);
        const double speed =
            std::max(std::hypot(p.handle_twist[0], p.handle_twist[1], p.handle_twist[2]),
                     std::hypot(last.handle_twist[0], last.handle_twist[1], last.handle_twist[2]));
        coupling_step_ = std::max(coupling_step_.load(), coupling / gap);
        coupling_excess_ =
            std::max(coupling_excess_.load(), coupling / gap - rate_step_ - max_damping_ * speed);
        ++cycles_;
      }
      last = p;
      last_rendering_ = rendering;
      have_last = true;
    }
  }

  void follow_operator_force() {
    shm::ForcePayload f;
    const shm::ReadResult r = segment_.region<shm::RegionId::kForce>().read(f);
    if (!r.ok() || r.sequence == last_force_sequence_) {
      return;
    }
    if (last_force_sequence_ != 0 && r.publish_time_ns > last_force_ns_) {
      const double dt = static_cast<double>(r.publish_time_ns - last_force_ns_) * 1e-9;
      for (std::size_t i = 0; i < 3; ++i) {
        const double rate = std::abs(f.wrench[i] - last_force_.wrench[i]) / dt;
        operator_rate_ = std::max(operator_rate_.load(), rate);
      }
    }
    last_force_sequence_ = r.sequence;
    last_force_ns_ = r.publish_time_ns;
    last_force_ = f;
  }

  const shm::Segment& segment_;
  std::atomic<bool> running_{true};
  double rate_step_;
  double max_damping_;
  std::atomic<double> coupling_step_{0.0};
  std::atomic<double> coupling_excess_{-1e9};
  std::atomic<double> operator_rate_{0.0};
  bool last_rendering_ = false;
  std::uint64_t last_force_sequence_ = 0;
  std::atomic<std::int64_t> last_force_ns_{0};
  shm::ForcePayload last_force_;
  std::atomic<bool> left_running_{false};
  std::atomic<std::uint64_t> cycles_{0};
  std::thread thread_;
};

/// The shipped arm model's limits (what the core runs with by default).
inline arm_model::ArmLimits arm_limits() {
  return arm_model::load_arm_model(arm_model::default_arm_model_path()).limits;
}
/// How fast the HMI ramps the operator's force, per axis [N/s].

}  // namespace hapticctrl::test
