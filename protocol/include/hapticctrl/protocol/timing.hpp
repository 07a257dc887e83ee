#pragma once
/// @file timing.hpp
/// The packed fields of CONTROL_OBJECT_TIMED (protocol 1.1, HCP_FEATURE_TIMING): the rotation
/// in "smallest three" form and the answer echo from which the bridge measures the link's round
/// trip and the core the coupling loop's delay (docs/protocol.md, docs/control.md).
///
/// Real-time contract: pure functions, no allocation, no syscall; safe in a cycle.
#include <array>
#include <cstdint>
#include <optional>

namespace hapticctrl::protocol {

/// {qx, qy, qz, qw}
using Quaternion = std::array<double, 4>;
using PackedRotation = std::array<std::uint32_t, 2>;

/// Packs a unit quaternion (normalised first; q and -q are the same rotation). A zero or
/// non-finite quaternion packs as the identity.
[[nodiscard]] PackedRotation pack_rotation(const Quaternion& q) noexcept;
/// The unit quaternion, or nothing if the bits cannot come from pack_rotation (reserved bits
/// set, or the three components' squares exceed 1 or the largest one).
[[nodiscard]] std::optional<Quaternion> unpack_rotation(const PackedRotation& packed) noexcept;

/// Units of the hold time in the echo (10 µs) and the value that says "no answer to echo".
inline constexpr std::int64_t kEchoHoldUnitNs = 10'000;
inline constexpr std::uint32_t kEchoNoAnswer = 0xFFFFU;

/// What a control frame says about the newest answer its sender had.
struct AnswerEcho {
  std::uint16_t cycle_low = 0;  ///< low 16 bits of that answer's cycle
  std::int64_t hold_ns = 0;     ///< how long the client held it before sending (10 µs steps)
  bool valid = false;           ///< false: no answer yet, or held 655 ms or more
};

/// Packs the echo; `hold_ns` < 0 or >= 655.35 ms (or no answer) packs as "no answer".
[[nodiscard]] std::uint32_t pack_answer_echo(std::uint64_t cycle, std::int64_t hold_ns,
                                             bool have_answer) noexcept;
[[nodiscard]] AnswerEcho unpack_answer_echo(std::uint32_t word) noexcept;

/// The latest cycle <= `reference` whose low 16 bits are `low` (0 if none exists).
[[nodiscard]] std::uint64_t expand_cycle(std::uint16_t low, std::uint64_t reference) noexcept;

}  // namespace hapticctrl::protocol
