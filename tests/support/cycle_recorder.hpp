#pragma once
/// Records what the core rendered, cycle by cycle, from the outside: a thread wakes on every VP
/// publish (the futex the UDP bridge waits on) and copies the position region (handle pose and
/// twist, the wrench rendered on the handle, the state word). A cycle the thread missed shows as
/// a gap in the cycle numbers; the checks below account for gaps. For end-to-end tests that
/// judge the coupling through the real processes.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "hapticctrl/shm/segment.hpp"

namespace hapticctrl::test {

struct CycleRecord {
  std::uint64_t cycle = 0;
  std::uint32_t state_word = 0;
  std::uint32_t core_state = 0;
  double speed = 0.0;  ///< handle linear speed, m/s
  double force = 0.0;  ///< |linear wrench rendered on the handle|, N
  std::array<double, 3> wrench{};
  std::array<double, 3> position{};
  [[nodiscard]] bool coupled() const { return (state_word & shm::state_bits::kCoupled) != 0; }
  [[nodiscard]] bool stale() const { return (state_word & shm::state_bits::kClientStale) != 0; }
  [[nodiscard]] bool degraded() const { return (state_word & shm::state_bits::kDegraded) != 0; }
};

class CycleRecorder {
 public:
  explicit CycleRecorder(const shm::Segment& segment)
      : segment_(segment), thread_([this] { follow(); }) {}
  CycleRecorder(const CycleRecorder&) = delete;
  CycleRecorder& operator=(const CycleRecorder&) = delete;
  ~CycleRecorder() { stop(); }

  void stop() {
    running_ = false;
    if (thread_.joinable()) {
      thread_.join();
    }
  }
  /// A copy of everything recorded so far.
  [[nodiscard]] std::vector<CycleRecord> records() const {
    const std::lock_guard lock(mutex_);
    return records_;
  }
  /// The newest cycle recorded (0: none).
  [[nodiscard]] std::uint64_t newest_cycle() const {
    const std::lock_guard lock(mutex_);
    return records_.empty() ? 0 : records_.back().cycle;
  }

 private:
  void follow() {
    using namespace std::chrono_literals;
    const auto& vp = segment_.region<shm::RegionId::kVp>();
    const auto& position = segment_.region<shm::RegionId::kPosition>();
    std::uint64_t last_cycle = 0;
    while (running_) {
      vp.wait_for_publish(vp.sequence_word(), 50ms);
      // Position is published right after VP in the same commit: look until it has caught up.
      for (int attempt = 0; attempt < 20; ++attempt) {
        shm::PositionPayload p;
        if (position.read(p).ok() && p.cycle > last_cycle) {
          last_cycle = p.cycle;
          add(p);
          break;
        }
        std::this_thread::sleep_for(20us);
      }
    }
  }
  void add(const shm::PositionPayload& p) {
    CycleRecord r;
    r.cycle = p.cycle;
    r.state_word = p.state_word;
    r.core_state = p.core_state;
    r.speed = std::hypot(p.handle_twist[0], p.handle_twist[1], p.handle_twist[2]);
    r.wrench = {p.rendered_wrench[0], p.rendered_wrench[1], p.rendered_wrench[2]};
    r.force = std::hypot(r.wrench[0], r.wrench[1], r.wrench[2]);
    r.position = {p.handle_pose[0], p.handle_pose[1], p.handle_pose[2]};
    const std::lock_guard lock(mutex_);
    records_.push_back(r);
  }

  const shm::Segment& segment_;
  mutable std::mutex mutex_;
  std::vector<CycleRecord> records_;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

/// The largest change of the handle force per cycle between consecutive records, N per cycle
/// (a gap of n cycles divides the change by n).
inline double largest_force_step(const std::vector<CycleRecord>& r, std::size_t from = 0,
                                 std::size_t to = SIZE_MAX) {
  double largest = 0.0;
  for (std::size_t i = std::max<std::size_t>(from, 1); i < std::min(to, r.size()); ++i) {
    const auto gap = static_cast<double>(r[i].cycle - r[i - 1].cycle);
    const double step =
        std::hypot(r[i].wrench[0] - r[i - 1].wrench[0], r[i].wrench[1] - r[i - 1].wrench[1],
                   r[i].wrench[2] - r[i - 1].wrench[2]);
    largest = std::max(largest, step / gap);
  }
  return largest;
}

}  // namespace hapticctrl::test
