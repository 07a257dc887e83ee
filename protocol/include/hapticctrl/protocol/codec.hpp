#pragma once
/// @file codec.hpp
/// Encoding and decoding of hapticctrl protocol frames (protocol/hapticctrl_protocol.x).
///
/// Private to the UDP bridge and the client library: applications never see these types.
/// Everything here works on caller-provided fixed buffers through xdrmem (no allocation, no
/// syscall, no exception), so it is safe in a per-cycle path.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "hapticctrl_protocol.h"

namespace hapticctrl::protocol {

inline constexpr std::size_t kMaxFrameBytes = HCP_MAX_FRAME_BYTES;
inline constexpr std::size_t kControlMaxBytes = HCP_CONTROL_MAX_BYTES;
/// Header (28) + body discriminant (4) + CRC (4): the smallest valid frame.
inline constexpr std::size_t kMinFrameBytes = 36;

using FrameBuffer = std::array<std::uint8_t, kMaxFrameBytes>;

/// Protocol versions are major << 16 | minor.
[[nodiscard]] constexpr std::uint32_t make_version(std::uint32_t major, std::uint32_t minor) {
  return (major << 16U) | (minor & 0xFFFFU);
}
[[nodiscard]] constexpr std::uint32_t version_major(std::uint32_t v) {
  return v >> 16U;
}
[[nodiscard]] constexpr std::uint32_t version_minor(std::uint32_t v) {
  return v & 0xFFFFU;
}
inline constexpr std::uint32_t kVersion = make_version(HCP_VERSION_MAJOR, HCP_VERSION_MINOR);
/// Every optional feature this build knows.
inline constexpr std::uint32_t kAllFeatures = HCP_FEATURE_JOINT_STATE | HCP_FEATURE_LINK_STATS |
                                              HCP_FEATURE_TIMING | HCP_FEATURE_LOCAL_COUPLING |
                                              HCP_FEATURE_JOINT_CONTROL;

/// Why a datagram is not a usable frame; each value is a separate drop counter in the bridge.
enum class DecodeStatus : std::uint8_t {
  kOk,
  kBadSize,  ///< shorter than a header + CRC, or longer than kMaxFrameBytes
  kBadMagic,
  kBadCrc,
  kBadVersion,  ///< another major version (only HELLO and REFUSE decode across versions)
  kMalformed,   ///< XDR decoding failed, unknown type/enum, or trailing bytes
  kOutOfRange,  ///< decoded, but a value is non-finite or outside its range (values.hpp)
};

/// Short stable name of a status ("crc", "magic", ...) for counters and logs.
[[nodiscard]] std::string_view to_string(DecodeStatus status) noexcept;

/// Encodes `frame` (its crc32 field is computed and set) into `out`.
/// Returns the frame's length, or 0 if it does not fit or does not encode.
/// Real-time contract: no allocation, no syscall; safe in a cycle.
std::size_t encode(hcp_frame& frame, std::span<std::uint8_t> out) noexcept;

/// Decodes and validates one datagram into `frame`: size, magic, CRC, version, XDR, then
/// values (every number finite and in range). On kBadVersion and kOutOfRange `frame.header`
/// is valid (so a HELLO of another version can be answered).
/// Real-time contract: no allocation, no syscall; safe in a cycle.
DecodeStatus decode(std::span<const std::uint8_t> bytes, hcp_frame& frame) noexcept;

/// A frame with the header filled for this build's version.
[[nodiscard]] hcp_frame make_frame(hcp_frame_type type, std::uint64_t token, std::uint32_t sequence,
                                   std::int64_t sender_time_ns) noexcept;

/// Copies `text` into a fixed NUL-padded opaque field (truncated to fit, always terminated).
template <std::size_t N>
void set_text(char (&field)[N], std::string_view text) noexcept {  // NOLINT(*-avoid-c-arrays)
  std::size_t n = text.size() < N - 1 ? text.size() : N - 1;
  for (std::size_t i = 0; i < N; ++i) {
    field[i] = i < n ? text[i] : '\0';
  }
}

/// The text of a NUL-padded opaque field (stops at the first NUL or the field's end).
template <std::size_t N>
[[nodiscard]] std::string_view text_of(
    const char (&field)[N]) noexcept {  // NOLINT(*-avoid-c-arrays)
  std::size_t n = 0;
  while (n < N && field[n] != '\0') {
    ++n;
  }
  return {static_cast<const char*>(field), n};
}

/// Copies a std::array (or any indexable) into a fixed XDR array field, converting each element
/// (double to float for control frames). Real-time contract: no allocation.
template <typename From, typename To, std::size_t N>
void to_wire(const From& from, To (&to)[N]) noexcept {  // NOLINT(*-avoid-c-arrays): XDR's shape
  for (std::size_t i = 0; i < N; ++i) {
    to[i] = static_cast<To>(from[i]);
  }
}

/// Copies a fixed XDR array field into a std::array, converting each element.
template <typename From, std::size_t N, typename To>
void from_wire(const From (&from)[N], To& to) noexcept {  // NOLINT(*-avoid-c-arrays)
  for (std::size_t i = 0; i < N; ++i) {
    to[i] = static_cast<typename To::value_type>(from[i]);
  }
}

/// RFC 1982 serial-number order for 32-bit sequences: true if `a` is newer than `b`.
[[nodiscard]] constexpr bool sequence_newer(std::uint32_t a, std::uint32_t b) noexcept {
  return a != b && static_cast<std::uint32_t>(a - b) < 0x80000000U;
}

}  // namespace hapticctrl::protocol
