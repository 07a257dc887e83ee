// Implements segment.hpp: creating (core) and attaching (everyone else) the shared-memory segment
// of one instance.
#include "hapticctrl/shm/segment.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <utility>

#include "hapticctrl/shm/segment_handoff.hpp"
#include "instance_lock.hpp"

namespace hapticctrl::shm {
namespace {

void* map_part(int fd, std::size_t offset, std::size_t length, bool writable,
               const std::string& what) {
  const int prot = writable ? (PROT_READ | PROT_WRITE) : PROT_READ;
  void* address = mmap(nullptr, length, prot, MAP_SHARED, fd, static_cast<off_t>(offset));
  if (address == MAP_FAILED) {
    throw_system_error("mmap " + what, errno);
  }
  return address;
}

void unmap(void*& address, std::size_t length) noexcept {
  if (address != nullptr) {
    munmap(address, length);
    address = nullptr;
  }
}

/// Tries to take a claim word: free, already ours, or left by a dead process.
/// Returns 0 on success, otherwise the live owner's packed identity.
std::uint64_t try_claim(std::atomic<std::uint64_t>& word, std::uint64_t mine) {
  std::uint64_t current = word.load(std::memory_order_acquire);
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (current == mine) {
      return 0;
    }
    if (current != 0 && packed_identity_alive(current)) {
      return current;
    }
    if (word.compare_exchange_strong(current, mine, std::memory_order_acq_rel)) {
      return 0;
    }
  }
  return current;
}

/// Whether the process behind a pidfd still runs (poll: readable once it has exited).
bool process_running(int pidfd) {
  pollfd watched{pidfd, POLLIN, 0};
  return poll(&watched, 1, 0) == 0;
}

}  // namespace

Segment Segment::create(const CreateOptions& options) {
  Segment seg;
  seg.instance_ = options.instance;
  seg.paths_ = InstancePaths::in(creator_runtime_directory(), options.instance);
  const gid_t group =
      options.group.empty() ? static_cast<gid_t>(-1) : static_cast<gid_t>(group_id(options.group));
  prepare_runtime_directory(seg.paths_.directory, group);
  seg.creator_ = true;
  seg.lock_fd_ = acquire_instance_lock(seg.paths_, options.instance);
  const LockRecord previous = read_lock_record(seg.lock_fd_);
  seg.fd_ = create_sealed_segment("hapticctrl." + options.instance, kSegmentSize);

  // Construct every object once through a temporary full mapping, then map per role.
  {
    void* all = map_part(seg.fd_, 0, kSegmentSize, true, "segment");
    auto* base = static_cast<unsigned char*>(all);
    auto* header = new (base + 0) SegmentHeader();
    new (base + kClaimsOffset) ClaimTable();
    new (base + region_offset(RegionId::kVpr)) RegionType<RegionId::kVpr>();
    new (base + region_offset(RegionId::kVp)) RegionType<RegionId::kVp>();
    new (base + region_offset(RegionId::kForce)) RegionType<RegionId::kForce>();
    new (base + region_offset(RegionId::kPosition)) RegionType<RegionId::kPosition>();
    new (base + region_offset(RegionId::kCtrl)) RegionType<RegionId::kCtrl>();
    new (base + region_offset(RegionId::kCtrlAck)) RegionType<RegionId::kCtrlAck>();
    new (base + region_offset(RegionId::kTelemetry)) RegionType<RegionId::kTelemetry>();
    new (base + region_offset(RegionId::kLinkStats)) RegionType<RegionId::kLinkStats>();
    new (base + region_offset(RegionId::kEvents)) RegionType<RegionId::kEvents>();
    new (base + region_offset(RegionId::kBlackBox)) RegionType<RegionId::kBlackBox>();
    const ProcessIdentity me = ProcessIdentity::self();
    header->abi_version = kAbiVersion;
    header->header_size = sizeof(SegmentHeader);
    header->segment_size = kSegmentSize;
    header->generation = previous.generation + 1;
    header->creator_pid = me.pid;
    header->creator_start_ticks = me.start_ticks;
    header->period_ns = options.period_ns;
    std::copy_n(options.instance.begin(),
                std::min(options.instance.size(), header->instance.size() - 1),
                header->instance.begin());
    for (std::size_t i = 0; i < kRegionCount; ++i) {
      header->regions[i] = RegionEntry{region_offset(static_cast<RegionId>(i)), kRegionSizes[i]};
    }
    munmap(all, kSegmentSize);
  }

  seg.header_part_ = Part{map_part(seg.fd_, 0, kClaimsOffset, true, "header"), kClaimsOffset, true};
  seg.header_ = static_cast<const SegmentHeader*>(seg.header_part_.address);
  seg.claims_part_ =
      Part{map_part(seg.fd_, kClaimsOffset, kFirstRegionOffset - kClaimsOffset, true, "claims"),
           kFirstRegionOffset - kClaimsOffset, true};
  const std::vector<RegionId> core_writes{RegionId::kVp,      RegionId::kPosition,
                                          RegionId::kCtrlAck, RegionId::kTelemetry,
                                          RegionId::kEvents,  RegionId::kBlackBox};
  seg.my_claim_ = pack_identity(ProcessIdentity::self());
  seg.claim_regions(core_writes);
  seg.map_regions(core_writes);
  seg.header_for_writing().core_state.store(static_cast<std::uint32_t>(CoreState::kStarting),
                                            std::memory_order_relaxed);
  seg.header_for_writing().magic.store(kSegmentMagic, std::memory_order_release);
  write_lock_record(seg.lock_fd_, LockRecord{getpid(), seg.header_->generation});
  seg.server_ = std::make_unique<SegmentServer>(seg.paths_, seg.fd_, group);
  return seg;
}

std::optional<Segment> Segment::try_attach(std::string_view instance,
                                           const AttachOptions& options) {
  try {
    return attach(instance, options);
  } catch (const ShmError& e) {
    if (e.code() == ShmErrc::kNoController) {
      return std::nullopt;
    }
    throw;
  }
}

Segment Segment::attach(std::string_view instance, const AttachOptions& options) {
  Segment seg;
  seg.instance_ = std::string(instance);
  const bool writes = !options.write.empty() || options.ctrl_writer;
  HandedSegment handed = request_segment(instance, writes);
  seg.fd_ = handed.segment.release();
  seg.core_fd_ = handed.core.release();

  seg.header_part_ =
      Part{map_part(seg.fd_, 0, kClaimsOffset, false, "header"), kClaimsOffset, false};
  seg.header_ = static_cast<const SegmentHeader*>(seg.header_part_.address);
  const SegmentHeader& header = *seg.header_;
  if (header.magic.load(std::memory_order_acquire) != kSegmentMagic) {
    throw ShmError(ShmErrc::kNoController,
                   "instance '" + seg.instance_ +
                       "' is not ready (its segment has no valid header: the core is starting "
                       "or has stopped)");
  }
  if (header.abi_version != kAbiVersion) {
    throw ShmError(ShmErrc::kAbiMismatch,
                   "ABI mismatch on instance '" + seg.instance_ + "': the running core uses " +
                       "shared-memory ABI v" + std::to_string(header.abi_version) +
                       ", this program v" + std::to_string(kAbiVersion) +
                       "; rebuild so that all hapticctrl programs come from one version");
  }
  bool layout_ok =
      header.header_size == sizeof(SegmentHeader) && header.segment_size == kSegmentSize;
  for (std::size_t i = 0; i < kRegionCount && layout_ok; ++i) {
    layout_ok = header.regions[i].offset == region_offset(static_cast<RegionId>(i)) &&
                header.regions[i].size == kRegionSizes[i];
  }
  if (!layout_ok) {
    throw ShmError(ShmErrc::kLayoutMismatch,
                   "layout mismatch on instance '" + seg.instance_ + "' (same ABI v" +
                       std::to_string(kAbiVersion) + " but different region sizes or offsets): " +
                       "rebuild so that all hapticctrl programs come from one version");
  }
  if (!seg.core_alive()) {
    throw ShmError(ShmErrc::kNoController, "no controller is running for instance '" +
                                               seg.instance_ + "': its core (pid " +
                                               std::to_string(header.creator_pid) +
                                               ") stopped while this process attached");
  }

  if (writes) {
    seg.claims_part_ =
        Part{map_part(seg.fd_, kClaimsOffset, kFirstRegionOffset - kClaimsOffset, true, "claims"),
             kFirstRegionOffset - kClaimsOffset, true};
    seg.my_claim_ = pack_identity(ProcessIdentity::self());
    seg.claim_regions(options.write);
  }
  std::vector<RegionId> writable = options.write;
  if (options.ctrl_writer) {
    writable.push_back(RegionId::kCtrl);
  }
  seg.map_regions(writable);
  if (options.ctrl_writer) {
    seg.claim_ctrl_slot();
  }
  return seg;
}

void Segment::claim_regions(const std::vector<RegionId>& ids) {
  auto* claims = static_cast<ClaimTable*>(claims_part_.address);
  for (const RegionId id : ids) {
    if (id == RegionId::kCtrl) {
      throw std::logic_error("ctrl has one writer per slot: use AttachOptions::ctrl_writer");
    }
    const auto index = static_cast<std::size_t>(id);
    const std::uint64_t owner = try_claim(claims->region_writer[index], my_claim_);
    if (owner != 0) {
      release_claims();
      const ProcessIdentity who = unpack_identity(owner);
      throw ShmError(ShmErrc::kWriterConflict,
                     "region " + std::string(region_name(id)) + " of instance '" + instance_ +
                         "' is already written by live process " + std::to_string(who.pid) +
                         " (one writer per region); stop that process first",
                     id);
    }
    claimed_[index] = true;
  }
}

void Segment::claim_ctrl_slot() {
  auto* claims = static_cast<ClaimTable*>(claims_part_.address);
  for (std::size_t slot = 0; slot < kCtrlSlots; ++slot) {
    if (try_claim(claims->ctrl_writer[slot], my_claim_) == 0) {
      ctrl_slot_ = slot;
      auto& region =
          *static_cast<CtrlRegion*>(parts_[static_cast<std::size_t>(RegionId::kCtrl)].address);
      const auto& acks = *static_cast<const CtrlAckRegion*>(
          parts_[static_cast<std::size_t>(RegionId::kCtrlAck)].address);
      ctrl_writer_.emplace(region.slots[slot], acks.slots[slot], slot);
      return;
    }
  }
  release_claims();
  throw ShmError(ShmErrc::kWriterConflict, "all " + std::to_string(kCtrlSlots) +
                                               " ctrl slots of instance '" + instance_ +
                                               "' are held by live processes");
}

void Segment::map_regions(const std::vector<RegionId>& writable_ids) {
  for (std::size_t i = 0; i < kRegionCount; ++i) {
    const auto id = static_cast<RegionId>(i);
    const bool writable =
        std::find(writable_ids.begin(), writable_ids.end(), id) != writable_ids.end();
    const std::size_t length = round_to_pages(kRegionSizes[i]);
    parts_[i] =
        Part{map_part(fd_, region_offset(id), length, writable, std::string(region_name(id))),
             length, writable};
  }
}

void Segment::require_writer(RegionId id) const {
  const auto index = static_cast<std::size_t>(id);
  if (!parts_[index].writable || (id != RegionId::kCtrl && !claimed_[index])) {
    throw std::logic_error("this process is not the writer of region " +
                           std::string(region_name(id)));
  }
}

SegmentHeader& Segment::header_for_writing() {
  if (!creator_) {
    throw std::logic_error("only the core writes the segment header");
  }
  return *static_cast<SegmentHeader*>(header_part_.address);
}

CtrlWriter& Segment::ctrl_writer() {
  if (!ctrl_writer_) {
    throw std::logic_error("this process did not claim a ctrl slot (AttachOptions::ctrl_writer)");
  }
  return *ctrl_writer_;
}

CtrlReader Segment::ctrl_reader() {
  if (!creator_) {
    throw std::logic_error("only the core consumes ctrl commands");
  }
  return CtrlReader(region<RegionId::kCtrl>(), writable<RegionId::kCtrlAck>());
}

bool Segment::core_alive() const {
  return creator_ || (core_fd_ >= 0 && process_running(core_fd_));
}

bool Segment::still_current() const {
  return header_ != nullptr && header_->magic.load(std::memory_order_acquire) == kSegmentMagic &&
         core_alive();
}

std::uint64_t Segment::refused_attaches() const noexcept {
  return server_ ? server_->refused() : 0;
}

std::optional<ProcessIdentity> Segment::writer_of(RegionId id) const {
  if (claims_part_.address == nullptr) {
    return std::nullopt;
  }
  const auto* claims = static_cast<const ClaimTable*>(claims_part_.address);
  const std::uint64_t word =
      claims->region_writer[static_cast<std::size_t>(id)].load(std::memory_order_acquire);
  if (!packed_identity_alive(word)) {
    return std::nullopt;
  }
  return unpack_identity(word);
}

void Segment::release_claims() noexcept {
  if (claims_part_.address == nullptr || my_claim_ == 0) {
    return;
  }
  auto* claims = static_cast<ClaimTable*>(claims_part_.address);
  for (std::size_t i = 0; i < kRegionCount; ++i) {
    if (claimed_[i]) {
      std::uint64_t expected = my_claim_;
      claims->region_writer[i].compare_exchange_strong(expected, 0, std::memory_order_acq_rel);
      claimed_[i] = false;
    }
  }
  if (ctrl_slot_) {
    std::uint64_t expected = my_claim_;
    claims->ctrl_writer[*ctrl_slot_].compare_exchange_strong(expected, 0,
                                                             std::memory_order_acq_rel);
    ctrl_slot_.reset();
    ctrl_writer_.reset();
  }
}

void Segment::close() noexcept {
  server_.reset();  // first: nobody attaches to a segment that is going away
  release_claims();
  if (creator_ && header_part_.address != nullptr) {
    auto* header = static_cast<SegmentHeader*>(header_part_.address);
    header->core_state.store(static_cast<std::uint32_t>(CoreState::kStopped),
                             std::memory_order_release);
    header->magic.store(0, std::memory_order_release);
  }
  for (auto& part : parts_) {
    unmap(part.address, part.length);
  }
  unmap(claims_part_.address, claims_part_.length);
  unmap(header_part_.address, header_part_.length);
  header_ = nullptr;
  if (creator_ && lock_fd_ >= 0) {
    unlink(paths_.lock.c_str());  // while still holding the flock (see acquire_instance_lock)
  }
  for (int* fd : {&fd_, &lock_fd_, &core_fd_}) {
    if (*fd >= 0) {
      ::close(*fd);
      *fd = -1;
    }
  }
  creator_ = false;
}

Segment::Segment(Segment&& other) noexcept {
  *this = std::move(other);
}

Segment& Segment::operator=(Segment&& other) noexcept {
  if (this != &other) {
    close();
    instance_ = std::move(other.instance_);
    paths_ = std::move(other.paths_);
    fd_ = std::exchange(other.fd_, -1);
    lock_fd_ = std::exchange(other.lock_fd_, -1);
    core_fd_ = std::exchange(other.core_fd_, -1);
    server_ = std::move(other.server_);
    creator_ = std::exchange(other.creator_, false);
    my_claim_ = std::exchange(other.my_claim_, 0);
    header_ = std::exchange(other.header_, nullptr);
    header_part_ = std::exchange(other.header_part_, Part{});
    claims_part_ = std::exchange(other.claims_part_, Part{});
    parts_ = std::exchange(other.parts_, {});
    claimed_ = std::exchange(other.claimed_, {});
    ctrl_slot_ = std::exchange(other.ctrl_slot_, std::nullopt);
    ctrl_writer_ = std::exchange(other.ctrl_writer_, std::nullopt);
  }
  return *this;
}

Segment::~Segment() {
  close();
}

}  // namespace hapticctrl::shm
