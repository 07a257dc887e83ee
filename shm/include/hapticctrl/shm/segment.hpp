#pragma once
/// @file segment.hpp
/// Creating (core) and attaching (everyone else) the shared-memory segment of one instance.
///
/// Every function here is setup code: it may allocate, make syscalls and throw ShmError.
/// The references it hands out (regions, ctrl writer/reader) are what the cycle then uses.

#include <sys/types.h>

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/layout.hpp"
#include "hapticctrl/shm/process_identity.hpp"

namespace hapticctrl::shm {

/// Why a create or attach failed; every value comes with a message that says what to do.
enum class ShmErrc : std::uint8_t {
  kBadInstanceName,
  kAlreadyRunning,    ///< create: a live core owns the instance
  kNoController,      ///< attach: no segment, or it was left by a dead core
  kAbiMismatch,       ///< attach: segment built by another ABI version
  kLayoutMismatch,    ///< attach: sizes/offsets differ from this program's
  kPermissionDenied,  ///< the OS refused access
  kInsecure,          ///< segment accessible by others than owner/group, or foreign owner
  kWriterConflict,    ///< another live process already writes that region / no free ctrl slot
  kSystem,            ///< any other OS error (message has errno text)
};

/// Exception for every setup failure of the shm layer.
class ShmError : public std::runtime_error {
 public:
  ShmError(ShmErrc code, const std::string& message) : std::runtime_error(message), code_(code) {}
  [[nodiscard]] ShmErrc code() const noexcept { return code_; }

 private:
  ShmErrc code_;
};

/// Options for Segment::create().
struct CreateOptions {
  std::string instance = "default";
  std::string group;  ///< group owning the segment (mode 0660); empty: the creator's group
  std::int64_t period_ns = 1'000'000;
};

/// Options for Segment::attach().
struct AttachOptions {
  std::vector<RegionId> write;  ///< regions this process writes: claimed, mapped read-write
  bool ctrl_writer = false;     ///< claim one ctrl slot to send commands
};

/// `/dev/shm` object names of an instance (validated).
struct SegmentNames {
  std::string segment;  ///< e.g. "/hapticctrl.default"
  std::string lock;     ///< e.g. "/hapticctrl.default.lock"
  /// Throws ShmError(kBadInstanceName) unless `instance` is 1-32 of [A-Za-z0-9_-].
  static SegmentNames of(std::string_view instance);
};

/// One process's view of an instance's segment. Move-only; unmaps and releases claims on
/// destruction; the creator also removes the segment's names (no leftovers in /dev/shm).
class Segment {
 public:
  /// Creates the instance (the core). Replaces a segment left by a dead core; refuses if a live
  /// core owns it (kAlreadyRunning, with its pid). Mode 0660, optional group.
  static Segment create(const CreateOptions& options);

  /// Attaches to a running instance. Regions not in `options.write` are mapped read-only.
  static Segment attach(std::string_view instance, const AttachOptions& options = {});

  Segment(Segment&& other) noexcept;
  Segment& operator=(Segment&& other) noexcept;
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;
  ~Segment();

  /// Real-time contract for every accessor below: safe in the cycle (no syscall).
  [[nodiscard]] const SegmentHeader& header() const noexcept { return *header_; }
  /// The creator's writable header (heartbeat, state). Throws std::logic_error otherwise.
  [[nodiscard]] SegmentHeader& header_for_writing();

  template <RegionId Id>
  [[nodiscard]] const RegionType<Id>& region() const noexcept {
    return *static_cast<const RegionType<Id>*>(parts_[static_cast<std::size_t>(Id)].address);
  }
  /// Writable view of a region this process claimed; throws std::logic_error otherwise.
  template <RegionId Id>
  [[nodiscard]] RegionType<Id>& writable() {
    require_writer(Id);
    return *static_cast<RegionType<Id>*>(parts_[static_cast<std::size_t>(Id)].address);
  }

  /// The claimed ctrl slot's writer (attach with ctrl_writer). Throws std::logic_error otherwise.
  [[nodiscard]] CtrlWriter& ctrl_writer();
  /// The consumer side of ctrl (creator only). Throws std::logic_error otherwise.
  [[nodiscard]] CtrlReader ctrl_reader();

  [[nodiscard]] bool is_creator() const noexcept { return creator_; }
  [[nodiscard]] const std::string& instance() const noexcept { return instance_; }
  /// Whether a live core holds the instance lock: two flock calls on a descriptor opened at
  /// attach, a few microseconds. Not for the cycle.
  [[nodiscard]] bool core_alive() const;
  /// Whether the instance's name still refers to this segment (false once a new core replaced
  /// it, or after the core removed it). Not for the cycle.
  [[nodiscard]] bool still_current() const;
  /// Identity of the live writer of a region, if any (diagnostics).
  [[nodiscard]] std::optional<ProcessIdentity> writer_of(RegionId id) const;

  /// Unmaps everything, releases claims, and (creator) removes the names. Idempotent; the
  /// destructor calls it.
  void close() noexcept;

 private:
  struct Part {
    void* address = nullptr;
    std::size_t length = 0;
    bool writable = false;
  };

  Segment() = default;
  void require_writer(RegionId id) const;
  void claim_regions(const std::vector<RegionId>& ids);
  void claim_ctrl_slot();
  void map_regions(const std::vector<RegionId>& writable_ids);
  void release_claims() noexcept;

  std::string instance_;
  SegmentNames names_;
  int fd_ = -1;
  int lock_fd_ = -1;  ///< creator: holds the exclusive flock; others: probes it
  bool creator_ = false;
  std::uint64_t my_claim_ = 0;
  const SegmentHeader* header_ = nullptr;
  Part header_part_;
  Part claims_part_;
  std::array<Part, kRegionCount> parts_{};
  std::array<bool, kRegionCount> claimed_{};
  std::optional<std::size_t> ctrl_slot_;
  std::optional<CtrlWriter> ctrl_writer_;
};

}  // namespace hapticctrl::shm
