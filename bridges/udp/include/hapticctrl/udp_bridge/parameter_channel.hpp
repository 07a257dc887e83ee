#pragma once
/// @file parameter_channel.hpp
/// The bridge's end of a session's parameter channel: each PARAM applied once, in order, and
/// acknowledged; a retransmission of the last one (its ACK was lost) acknowledged again without
/// being applied; an older one dropped. And what a PARAM does: a field of VPr, the watchdog, or
/// a command for the controller's ctrl queue.
///
/// Real-time contract: noexcept, no allocation, no syscall (the bridge's receive thread).
#include <cstdint>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::udp_bridge {

/// One acknowledgement as sent (and replayed).
struct ParamAck {
  std::uint32_t sequence = 0;
  hcp_ack_status status = HCP_ACK_OK;
  char reason[HCP_TEXT_BYTES] = {};  // NOLINT(*-avoid-c-arrays): the XDR field's shape
};

class ParameterChannel {
 public:
  /// What to do with a PARAM of a given sequence number.
  enum class Step : std::uint8_t {
    kApply,   ///< new: apply, then record() its ACK
    kReplay,  ///< the last one again: send last() again
    kStale,   ///< older than the last: drop (counted as a sequence drop)
  };

  /// A new session: no PARAM yet.
  void reset() noexcept { *this = ParameterChannel{}; }
  [[nodiscard]] Step step_for(std::uint32_t sequence) const noexcept;
  /// The ACK of an applied (or rejected) PARAM: replayed if the same sequence comes again. An
  /// ACK of RETRY is not recorded (the retransmission applies).
  void record(const ParamAck& ack) noexcept;
  [[nodiscard]] const ParamAck& last() const noexcept { return last_; }

 private:
  bool have_sequence_ = false;
  ParamAck last_{};
};

/// What applying a PARAM asks of the bridge beyond VPr.
struct ParamEffect {
  shm::CtrlCode ctrl = shm::CtrlCode::kNone;  ///< a command for the controller (kNone: none)
  std::uint32_t ctrl_arg = 0;
};

/// Applies a validated PARAM to the session's VPr and watchdog (capped at `max_watchdog_ms`).
/// Changing the command type clears the joint fields of the mode before.
[[nodiscard]] ParamEffect apply_param(const hcp_param& param, std::uint32_t max_watchdog_ms,
                                      shm::VprPayload& vpr, std::uint32_t& watchdog_ms) noexcept;

/// Whether `param` needs a feature the session did not negotiate (the joint-space command types
/// need protocol 1.4's JOINT_CONTROL); the ACK's reason when it does, else nullptr.
[[nodiscard]] const char* missing_feature(const hcp_param& param, std::uint32_t features) noexcept;

}  // namespace hapticctrl::udp_bridge
