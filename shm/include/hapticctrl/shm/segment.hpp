#pragma once
/// @file segment.hpp
/// Creating (core) and attaching (everyone else) the shared-memory segment of one instance.
///
/// Every function here is setup code: it may allocate, make syscalls and throw ShmError.
/// The references it hands out (regions, ctrl writer/reader) are what the cycle then uses.

#include <sys/types.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/error.hpp"
#include "hapticctrl/shm/layout.hpp"
#include "hapticctrl/shm/process_identity.hpp"
#include "hapticctrl/shm/rendezvous.hpp"

namespace hapticctrl::shm {

class SegmentServer;

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

/// One process's view of an instance's segment. Move-only; unmaps and releases claims on
/// destruction. The segment is a sealed memfd without a name (segment_handoff.hpp): it ends with
/// the last process that maps it, whatever way the core ends; the creator also removes its
/// socket and lock file (a core that died leaves them for the next one to reuse).
class Segment {
 public:
  /// Creates the instance (the core): takes the instance lock in the runtime directory (refuses
  /// kAlreadyRunning, with its pid, if a live core holds it), creates the sealed segment and
  /// serves it on the instance's socket (mode 0660, group `options.group`) to the core's user,
  /// root and members of that group.
  static Segment create(const CreateOptions& options);

  /// Attaches to a running instance: asks its core for the segment (segment_handoff.hpp), then
  /// checks the header. Regions not in `options.write` are mapped read-only, and a process that
  /// writes nothing holds a read-only descriptor.
  static Segment attach(std::string_view instance, const AttachOptions& options = {});
  /// attach(), or nullopt while no controller runs for the instance (a bridge waiting for its
  /// core); every other error throws as attach() does.
  static std::optional<Segment> try_attach(std::string_view instance,
                                           const AttachOptions& options = {});

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
  /// Whether the core that handed out this segment still runs: one poll of its pidfd, about
  /// 1.4 µs (2026-12-02). Not for the cycle.
  [[nodiscard]] bool core_alive() const;
  /// Whether this segment is still its core's live one (false once the core stopped, failed
  /// or died; a new core of the instance has a new segment). Not for the cycle.
  [[nodiscard]] bool still_current() const;
  /// Creator: requests for the segment refused so far (a peer outside the core's user, root and
  /// group, a malformed request, or silent for 200 ms). Any thread.
  [[nodiscard]] std::uint64_t refused_attaches() const noexcept;
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
  InstancePaths paths_;
  int fd_ = -1;
  int lock_fd_ = -1;  ///< creator: holds the instance's exclusive flock
  int core_fd_ = -1;  ///< attacher: a pidfd of the core
  std::unique_ptr<SegmentServer> server_;
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
