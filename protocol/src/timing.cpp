// Implements timing.hpp: the packed fields of CONTROL_OBJECT_TIMED (protocol 1.1,
// HCP_FEATURE_TIMING).
#include "hapticctrl/protocol/timing.hpp"

#include <cmath>

namespace hapticctrl::protocol {
namespace {

constexpr double kComponentBound = 0.70710678118654752;  // 1/sqrt(2): the smallest three's range
constexpr std::uint32_t kFieldMax = (1U << 20U) - 1U;

std::uint32_t to_field(double x) noexcept {
  const double unit = (x + kComponentBound) / (2.0 * kComponentBound);
  const double scaled = std::round(unit * static_cast<double>(kFieldMax));
  return static_cast<std::uint32_t>(std::fmin(std::fmax(scaled, 0.0), kFieldMax));
}

double from_field(std::uint32_t f) noexcept {
  return static_cast<double>(f) / static_cast<double>(kFieldMax) * 2.0 * kComponentBound -
         kComponentBound;
}

}  // namespace

PackedRotation pack_rotation(const Quaternion& q_in) noexcept {
  double norm = 0.0;
  for (const double c : q_in) {
    norm += c * c;
  }
  norm = std::sqrt(norm);
  Quaternion q{0.0, 0.0, 0.0, 1.0};
  if (std::isfinite(norm) && norm > 1e-9) {
    for (std::size_t i = 0; i < 4; ++i) {
      q[i] = q_in[i] / norm;
    }
  }
  std::size_t largest = 0;
  for (std::size_t i = 1; i < 4; ++i) {
    if (std::abs(q[i]) > std::abs(q[largest])) {
      largest = i;
    }
  }
  const double sign = q[largest] < 0.0 ? -1.0 : 1.0;
  std::array<std::uint32_t, 3> f{};
  for (std::size_t i = 0, k = 0; i < 4; ++i) {
    if (i != largest) {
      f[k++] = to_field(sign * q[i]);
    }
  }
  PackedRotation p{};
  p[0] = (static_cast<std::uint32_t>(largest) << 30U) | (f[0] << 10U) | (f[1] >> 10U);
  p[1] = ((f[1] & 0x3FFU) << 22U) | (f[2] << 2U);
  return p;
}

std::optional<Quaternion> unpack_rotation(const PackedRotation& p) noexcept {
  if ((p[1] & 0x3U) != 0U) {
    return std::nullopt;
  }
  const std::size_t largest = p[0] >> 30U;
  const std::array<std::uint32_t, 3> f{(p[0] >> 10U) & kFieldMax,
                                       ((p[0] & 0x3FFU) << 10U) | (p[1] >> 22U),
                                       (p[1] >> 2U) & kFieldMax};
  Quaternion q{};
  double sum = 0.0;
  double biggest_small = 0.0;
  for (std::size_t i = 0, k = 0; i < 4; ++i) {
    if (i != largest) {
      q[i] = from_field(f[k++]);
      sum += q[i] * q[i];
      biggest_small = std::fmax(biggest_small, std::abs(q[i]));
    }
  }
  if (sum > 1.0) {
    return std::nullopt;
  }
  q[largest] = std::sqrt(1.0 - sum);
  // pack_rotation only ever leaves out the largest component (20-bit rounding may tie it).
  if (q[largest] + 2e-6 < biggest_small) {
    return std::nullopt;
  }
  return q;
}

std::uint32_t pack_answer_echo(std::uint64_t cycle, std::int64_t hold_ns,
                               bool have_answer) noexcept {
  std::uint32_t hold = kEchoNoAnswer;
  if (have_answer && hold_ns >= 0) {
    const std::int64_t units = hold_ns / kEchoHoldUnitNs;
    hold = units < static_cast<std::int64_t>(kEchoNoAnswer) ? static_cast<std::uint32_t>(units)
                                                            : kEchoNoAnswer;
  }
  return (hold << 16U) | static_cast<std::uint32_t>(cycle & 0xFFFFU);
}

AnswerEcho unpack_answer_echo(std::uint32_t word) noexcept {
  AnswerEcho e;
  e.cycle_low = static_cast<std::uint16_t>(word & 0xFFFFU);
  const std::uint32_t hold = word >> 16U;
  e.valid = hold != kEchoNoAnswer;
  e.hold_ns = e.valid ? static_cast<std::int64_t>(hold) * kEchoHoldUnitNs : 0;
  return e;
}

std::uint64_t expand_cycle(std::uint16_t low, std::uint64_t reference) noexcept {
  const std::uint64_t candidate = (reference & ~std::uint64_t{0xFFFF}) | low;
  if (candidate <= reference) {
    return candidate;
  }
  return reference >= 0x10000U ? candidate - 0x10000U : 0;
}

}  // namespace hapticctrl::protocol
