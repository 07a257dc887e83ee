#pragma once
/// @file control_ingest.hpp
/// The bridge's intake of a session's control frames: their order (a replayed or reordered
/// frame is refused, the sequence extended to 64 bits), the link they came over (delay, jitter
/// and loss, from the answer echoes: link_timing.hpp), the client's channel energy, and what
/// each frame says (object state, IMPEDANCE wrench, joint command, contact) written into the
/// session's VPr.
///
/// Real-time contract: noexcept, no allocation, no syscall (the bridge's receive thread).
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/udp_bridge/link_timing.hpp"

namespace hapticctrl::udp_bridge {

/// The client link as this bridge measures it.
struct LinkFigures {
  Duration delay{};
  Duration jitter{};
  std::uint32_t loss_ppm = 0;
  std::uint32_t pad = 0;
};

class ControlIngest {
 public:
  /// `answers`: the send times of this bridge's answers (written by the answer thread).
  explicit ControlIngest(const AnswerLog& answers) noexcept : answers_(&answers) {}

  /// A new session: no frame yet, the link and the energy start from nothing.
  void reset() noexcept;
  /// Whether a control frame of `sequence` is newer than the last admitted (then it is counted
  /// as the next, and the sequence numbers it skipped as lost); false: drop it.
  [[nodiscard]] bool admit(std::uint32_t sequence) noexcept;
  /// The content of an admitted control frame (not KEEPALIVE) into `vpr`: a sample (object,
  /// wrench, joints) with its sequence, timing and the link's figures, or a contact slot.
  void take(const hcp_frame& in, TimePoint now, shm::VprPayload& vpr) noexcept;
  [[nodiscard]] LinkFigures link() const noexcept {
    return {link_.delay(), link_.jitter(), link_.loss_ppm(), 0};
  }

 private:
  void take_sample(const hcp_frame& in, TimePoint now, shm::VprPayload& vpr) noexcept;
  void take_timed_object(const hcp_control_object_timed& o, TimePoint now,
                         shm::VprPayload& vpr) noexcept;
  void take_timing(std::uint32_t answer_echo, std::uint32_t energy_in_uj, TimePoint now,
                   shm::VprPayload& vpr) noexcept;
  void take_contact(const hcp_control_contact& c, TimePoint now, shm::VprPayload& vpr) noexcept;

  /// A difference beyond 4 J in one frame (35 N at 100 m/s for 1 ms is 3.5 J) is not physical.
  static constexpr std::uint32_t kMaxEnergyStepUj = 4'000'000;

  const AnswerLog* answers_;
  bool have_sequence_ = false;
  std::uint32_t last_sequence_ = 0;
  std::uint64_t sequence_high_ = 0;  ///< 64-bit extension of the control sequence
  LinkEstimator link_;
  bool have_energy_ = false;
  std::uint32_t energy_in_last_ = 0;
  double energy_in_total_ = 0.0;
};

}  // namespace hapticctrl::udp_bridge
