#pragma once
/// @file layout.hpp
/// Layout of one controller instance's shared-memory segment.
///
/// One sealed memfd per instance (segment_handoff.hpp: the core hands it out, it has no name),
/// made of page-aligned parts so that each process can map each part with the protection its
/// role needs:
///
///   page 0          SegmentHeader   written by the core, read by all
///   page 1          ClaimTable      writer claims: written by any process that claims a role
///   then, per region (RegionId order), page-aligned:
///     VPr           written by the UDP bridge          (seqlock)
///     VP            written by the core                (seqlock, notified every cycle)
///     force         written by the HMI side            (seqlock)
///     position      written by the core                (seqlock, notified every cycle)
///     ctrl          written by up to kCtrlSlots writers (per-writer rings, see ctrl.hpp)
///     ctrl_ack      written by the core                (ring progress)
///     telemetry     written by the core                (seqlock)
///     link_stats    written by the UDP bridge          (seqlock)
///     events        written by the core                (ring, events.hpp)
///     blackbox      written by the core                (ring, black_box_ring.hpp)
///
/// The core's exclusive flock on `<runtime dir>/<instance>.lock` (rendezvous.hpp) makes it the
/// instance's only core; attached processes tell a live core from a dead one by its pidfd.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hapticctrl/shm/black_box_ring.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/events.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::shm {

/// Bumped on any change to payloads.hpp, ctrl.hpp or this file.
// 2: link_stats (F4); 3: events, histogram (F5); 4: telemetry vpr_rejected, link drops
// not_allowed and rate_limited (F8); 5: VPr sample time, echo cycle, link figures, client
// channel energy; VP the coupling loop figures, gains and channel energies (H1); 6: force
// carries a spring-damper hand (H1's operator model); telemetry would-be fail-safes (benchmark
// mode); 7: VPr the object's contacts, VP the coupling's contact stiffening and limits (J1,
// protocol 1.3); 8: the blackbox region (J4); 9: VP the surface rendered on the handle (J2);
// 10: VPr the joint-space commands (J6, protocol 1.4); 11: names that say their frame (VP
// object_wrench, client_handle_pose/twist; position rendered_wrench), the link figures in
// link_stats instead of a round trip through VP (J7); 12: force's hand has a wrist (J3)
inline constexpr std::uint32_t kAbiVersion = 12;
/// "HAPTICC1" as a little-endian word; stored last when the segment is ready, cleared at exit.
inline constexpr std::uint64_t kSegmentMagic = 0x3143434954504148ULL;
inline constexpr std::size_t kPageSize = 4096;

/// The regions of an instance, in layout order.
enum class RegionId : std::uint32_t {
  kVpr = 0,
  kVp,
  kForce,
  kPosition,
  kCtrl,
  kCtrlAck,
  kTelemetry,
  kLinkStats,
  kEvents,
  kBlackBox,
  kCount,
};
inline constexpr std::size_t kRegionCount = static_cast<std::size_t>(RegionId::kCount);

/// Human-readable region name ("VPr", "VP", ...), for messages.
[[nodiscard]] std::string_view region_name(RegionId id) noexcept;

/// The in-memory type of each region.
template <RegionId Id>
struct RegionTraits;
template <>
struct RegionTraits<RegionId::kVpr> {
  using Type = SeqlockCell<VprPayload>;
};
template <>
struct RegionTraits<RegionId::kVp> {
  using Type = SeqlockCell<VpPayload>;
};
template <>
struct RegionTraits<RegionId::kForce> {
  using Type = SeqlockCell<ForcePayload>;
};
template <>
struct RegionTraits<RegionId::kPosition> {
  using Type = SeqlockCell<PositionPayload>;
};
template <>
struct RegionTraits<RegionId::kCtrl> {
  using Type = CtrlRegion;
};
template <>
struct RegionTraits<RegionId::kCtrlAck> {
  using Type = CtrlAckRegion;
};
template <>
struct RegionTraits<RegionId::kTelemetry> {
  using Type = SeqlockCell<TelemetryPayload>;
};
template <>
struct RegionTraits<RegionId::kLinkStats> {
  using Type = SeqlockCell<LinkStatsPayload>;
};
template <>
struct RegionTraits<RegionId::kEvents> {
  using Type = EventRing;
};
template <>
struct RegionTraits<RegionId::kBlackBox> {
  using Type = BlackBoxRing;
};
template <RegionId Id>
using RegionType = typename RegionTraits<Id>::Type;

/// Where a region sits in the segment; recorded in the header and checked on attach.
struct RegionEntry {
  std::uint64_t offset = 0;
  std::uint64_t size = 0;  ///< sizeof the region type (the mapping is page-rounded)
};

/// The header page. Plain fields are written once before `magic` is stored with release.
struct SegmentHeader {
  std::atomic<std::uint64_t> magic{0};
  std::uint32_t abi_version = 0;
  std::uint32_t header_size = 0;
  std::uint64_t segment_size = 0;
  std::uint64_t generation = 0;  ///< +1 each time a core (re)creates this instance
  std::int32_t creator_pid = 0;
  std::uint32_t reserved0 = 0;
  std::uint64_t creator_start_ticks = 0;
  std::int64_t period_ns = 0;
  std::array<char, 48> instance{};
  std::array<RegionEntry, kRegionCount> regions{};
  std::atomic<std::uint32_t> core_state{0};       ///< CoreState
  std::atomic<std::uint32_t> stop_reason{0};      ///< StopReason
  std::atomic<std::uint64_t> heartbeat_cycle{0};  ///< advanced by the core every cycle
  std::atomic<std::int64_t> heartbeat_ns{0};      ///< CLOCK_MONOTONIC of the last heartbeat
};

/// Writer claims: one word per region (see WriterClaim), one per ctrl slot.
struct ClaimTable {
  std::array<std::atomic<std::uint64_t>, kRegionCount> region_writer{};
  std::array<std::atomic<std::uint64_t>, kCtrlSlots> ctrl_writer{};
};

/// Rounds `n` up to whole pages.
constexpr std::size_t round_to_pages(std::size_t n) noexcept {
  return (n + kPageSize - 1) / kPageSize * kPageSize;
}

inline constexpr std::array<std::size_t, kRegionCount> kRegionSizes{
    sizeof(RegionType<RegionId::kVpr>),       sizeof(RegionType<RegionId::kVp>),
    sizeof(RegionType<RegionId::kForce>),     sizeof(RegionType<RegionId::kPosition>),
    sizeof(RegionType<RegionId::kCtrl>),      sizeof(RegionType<RegionId::kCtrlAck>),
    sizeof(RegionType<RegionId::kTelemetry>), sizeof(RegionType<RegionId::kLinkStats>),
    sizeof(RegionType<RegionId::kEvents>),    sizeof(RegionType<RegionId::kBlackBox>)};

inline constexpr std::size_t kClaimsOffset = round_to_pages(sizeof(SegmentHeader));
inline constexpr std::size_t kFirstRegionOffset =
    kClaimsOffset + round_to_pages(sizeof(ClaimTable));

/// Page-aligned offset of a region (RegionId::kCount gives the segment size).
constexpr std::size_t region_offset(RegionId id) noexcept {
  std::size_t offset = kFirstRegionOffset;
  for (std::size_t i = 0; i < static_cast<std::size_t>(id); ++i) {
    offset += round_to_pages(kRegionSizes[i]);
  }
  return offset;
}

inline constexpr std::size_t kSegmentSize = region_offset(RegionId::kCount);

static_assert(sizeof(SegmentHeader) <= kPageSize);
static_assert(std::atomic<std::uint64_t>::is_always_lock_free);

}  // namespace hapticctrl::shm
