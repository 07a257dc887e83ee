#include "hapticctrl/shm/segment.hpp"

#include <fcntl.h>
#include <grp.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>
#include <string>
#include <utility>

namespace hapticctrl::shm {
namespace {

constexpr mode_t kSegmentMode = 0660;
constexpr std::size_t kMaxInstanceName = 32;
constexpr std::string_view kShmDir = "/dev/shm";

std::string errno_text(int error) {
  return std::strerror(error);
}

[[noreturn]] void throw_system(const std::string& what, int error) {
  if (error == EACCES || error == EPERM) {
    throw ShmError(ShmErrc::kPermissionDenied,
                   what +
                       ": permission denied (segments are mode 0660: run as the owner or a "
                       "member of the segment's group)");
  }
  throw ShmError(ShmErrc::kSystem, what + ": " + errno_text(error));
}

std::string shm_path(const std::string& name) {
  return std::string(kShmDir) + name;
}

gid_t resolve_group(const std::string& group) {
  std::string buffer(16384, '\0');
  struct group entry {};
  struct group* result = nullptr;
  int rc = ERANGE;
  while (rc == ERANGE && buffer.size() <= (1U << 20)) {
    rc = getgrnam_r(group.c_str(), &entry, buffer.data(), buffer.size(), &result);
    if (rc == ERANGE) {
      buffer.resize(buffer.size() * 2);
    }
  }
  if (rc != 0 || result == nullptr) {
    throw ShmError(ShmErrc::kSystem, "unknown group '" + group + "' for the shared-memory segment");
  }
  return entry.gr_gid;
}

/// mode 0660 regardless of umask, then the optional group.
void set_ownership(int fd, const std::string& what, const std::string& group) {
  if (fchmod(fd, kSegmentMode) != 0) {
    throw_system("chmod " + what, errno);
  }
  if (!group.empty() && fchown(fd, static_cast<uid_t>(-1), resolve_group(group)) != 0) {
    throw_system("chown " + what + " to group '" + group + "'", errno);
  }
}

void* map_part(int fd, std::size_t offset, std::size_t length, bool writable,
               const std::string& what) {
  const int prot = writable ? (PROT_READ | PROT_WRITE) : PROT_READ;
  void* address = mmap(nullptr, length, prot, MAP_SHARED, fd, static_cast<off_t>(offset));
  if (address == MAP_FAILED) {
    throw_system("mmap " + what, errno);
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

/// Reads the pid and generation of an existing segment, if it is one of ours.
struct OldSegmentInfo {
  pid_t creator_pid = 0;
  std::uint64_t generation = 0;
};

std::optional<OldSegmentInfo> peek_existing(const std::string& name) {
  const int fd = shm_open(name.c_str(), O_RDONLY | O_CLOEXEC, 0);
  if (fd < 0) {
    return std::nullopt;
  }
  std::optional<OldSegmentInfo> info;
  struct stat st {};
  if (fstat(fd, &st) == 0 && static_cast<std::size_t>(st.st_size) >= sizeof(SegmentHeader)) {
    void* address = mmap(nullptr, sizeof(SegmentHeader), PROT_READ, MAP_SHARED, fd, 0);
    if (address != MAP_FAILED) {
      const auto* header = static_cast<const SegmentHeader*>(address);
      if (header->magic.load(std::memory_order_acquire) == kSegmentMagic ||
          header->generation != 0) {
        info = OldSegmentInfo{header->creator_pid, header->generation};
      }
      munmap(address, sizeof(SegmentHeader));
    }
  }
  ::close(fd);
  return info;
}

/// The exclusive flock of a live core. Attached processes probe the lock with a shared flock held
/// for a few microseconds (Segment::core_alive, every 2 ms while a core is silent): a core
/// starting in that window retries instead of reporting a running instance that is not there.
bool take_exclusive_lock(int fd) {
  for (int attempt = 0;; ++attempt) {
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
      return true;
    }
    if (errno != EWOULDBLOCK || attempt == 3) {
      return false;
    }
    usleep(1000);
  }
}

/// Opens the lock object and takes the exclusive flock that marks a live core. Guards against
/// the classic unlink race: the lock we hold must still be the one the name points to.
int acquire_instance_lock(const SegmentNames& names, const std::string& instance,
                          const std::string& group) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    const int fd = shm_open(names.lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, kSegmentMode);
    if (fd < 0) {
      throw_system("open lock " + shm_path(names.lock), errno);
    }
    if (!take_exclusive_lock(fd)) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK) {
        const auto old = peek_existing(names.segment);
        throw ShmError(ShmErrc::kAlreadyRunning,
                       "instance '" + instance + "' is already running" +
                           (old ? " (core pid " + std::to_string(old->creator_pid) + ")" : "") +
                           "; stop it first or choose another --instance");
      }
      throw_system("lock " + shm_path(names.lock), error);
    }
    struct stat held {};
    struct stat named {};
    if (fstat(fd, &held) == 0 && stat(shm_path(names.lock).c_str(), &named) == 0 &&
        held.st_ino == named.st_ino) {
      try {
        set_ownership(fd, shm_path(names.lock), group);
      } catch (...) {
        shm_unlink(names.lock.c_str());  // we hold the lock: the name is ours to remove
        ::close(fd);
        throw;
      }
      return fd;
    }
    ::close(fd);  // the name was unlinked/replaced under us: try again
  }
  throw ShmError(ShmErrc::kSystem,
                 "could not take the lock of instance '" + instance + "' (it kept being replaced)");
}

void check_not_world_accessible(const struct stat& st, const std::string& what) {
  if ((st.st_mode & (S_IROTH | S_IWOTH)) != 0) {
    throw ShmError(ShmErrc::kInsecure,
                   what + " is accessible by other users (mode " +
                       std::to_string(st.st_mode & 0777) +
                       " decimal); refusing to use it. Remove it or fix its mode to 0660.");
  }
}

}  // namespace

SegmentNames SegmentNames::of(std::string_view instance) {
  const bool valid_chars = std::all_of(instance.begin(), instance.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
  if (instance.empty() || instance.size() > kMaxInstanceName || !valid_chars) {
    throw ShmError(ShmErrc::kBadInstanceName, "invalid instance name '" + std::string(instance) +
                                                  "': use 1 to 32 characters from [A-Za-z0-9_-]");
  }
  const std::string base = "/hapticctrl." + std::string(instance);
  return SegmentNames{base, base + ".lock"};
}

Segment Segment::create(const CreateOptions& options) {
  Segment seg;
  seg.instance_ = options.instance;
  seg.names_ = SegmentNames::of(options.instance);
  seg.creator_ = true;
  seg.lock_fd_ = acquire_instance_lock(seg.names_, options.instance, options.group);

  // We hold the lock, so any existing segment is stale (its core died): replace it. Readers that
  // still map the old one keep a valid (orphaned) mapping and notice via still_current().
  const auto old = peek_existing(seg.names_.segment);
  shm_unlink(seg.names_.segment.c_str());
  seg.fd_ =
      shm_open(seg.names_.segment.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, kSegmentMode);
  if (seg.fd_ < 0) {
    throw_system("create " + shm_path(seg.names_.segment), errno);
  }
  set_ownership(seg.fd_, shm_path(seg.names_.segment), options.group);
  if (ftruncate(seg.fd_, static_cast<off_t>(kSegmentSize)) != 0) {
    throw_system("size " + shm_path(seg.names_.segment), errno);
  }

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
    const ProcessIdentity me = ProcessIdentity::self();
    header->abi_version = kAbiVersion;
    header->header_size = sizeof(SegmentHeader);
    header->segment_size = kSegmentSize;
    header->generation = old ? old->generation + 1 : 1;
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
  const std::vector<RegionId> core_writes{RegionId::kVp, RegionId::kPosition, RegionId::kCtrlAck,
                                          RegionId::kTelemetry, RegionId::kEvents};
  seg.my_claim_ = pack_identity(ProcessIdentity::self());
  seg.claim_regions(core_writes);
  seg.map_regions(core_writes);
  seg.header_for_writing().core_state.store(static_cast<std::uint32_t>(CoreState::kStarting),
                                            std::memory_order_relaxed);
  seg.header_for_writing().magic.store(kSegmentMagic, std::memory_order_release);
  return seg;
}

Segment Segment::attach(std::string_view instance, const AttachOptions& options) {
  Segment seg;
  seg.instance_ = std::string(instance);
  seg.names_ = SegmentNames::of(instance);
  const bool writes = !options.write.empty() || options.ctrl_writer;
  const std::string path = shm_path(seg.names_.segment);

  seg.fd_ = shm_open(seg.names_.segment.c_str(), (writes ? O_RDWR : O_RDONLY) | O_CLOEXEC, 0);
  if (seg.fd_ < 0) {
    if (errno == ENOENT) {
      throw ShmError(ShmErrc::kNoController, "no controller is running for instance '" +
                                                 seg.instance_ + "' (" + path +
                                                 " does not exist); start hapticctrl-core first");
    }
    throw_system("open " + path, errno);
  }
  // Kept open to probe the core's lock cheaply (core_alive) for as long as we are attached.
  seg.lock_fd_ = shm_open(seg.names_.lock.c_str(), O_RDONLY | O_CLOEXEC, 0);
  if (seg.lock_fd_ < 0) {
    if (errno != ENOENT) {
      throw_system("open lock " + shm_path(seg.names_.lock), errno);
    }
    throw ShmError(ShmErrc::kNoController, "no controller is running for instance '" +
                                               seg.instance_ + "' (its lock " +
                                               shm_path(seg.names_.lock) + " is gone)");
  }
  struct stat st {};
  if (fstat(seg.fd_, &st) != 0) {
    throw_system("stat " + path, errno);
  }
  check_not_world_accessible(st, path);
  if (st.st_uid != geteuid() && geteuid() != 0 && st.st_uid != 0) {
    // Same-group access is allowed by the mode, but only to segments a trusted user created.
    struct stat lock_st {};
    if (stat(shm_path(seg.names_.lock).c_str(), &lock_st) != 0 || lock_st.st_uid != st.st_uid) {
      throw ShmError(ShmErrc::kInsecure,
                     path + " is owned by uid " + std::to_string(st.st_uid) +
                         " but its lock is not: refusing a segment planted by another user");
    }
  }
  if (static_cast<std::size_t>(st.st_size) < sizeof(SegmentHeader)) {
    throw ShmError(ShmErrc::kLayoutMismatch, path + " is " + std::to_string(st.st_size) +
                                                 " bytes, too small to be a " +
                                                 "hapticctrl segment");
  }

  seg.header_part_ =
      Part{map_part(seg.fd_, 0, kClaimsOffset, false, "header"), kClaimsOffset, false};
  seg.header_ = static_cast<const SegmentHeader*>(seg.header_part_.address);
  const SegmentHeader& header = *seg.header_;
  if (header.magic.load(std::memory_order_acquire) != kSegmentMagic) {
    throw ShmError(ShmErrc::kNoController,
                   "instance '" + seg.instance_ + "' is not ready (" + path +
                       " has no valid header: the core is starting or has stopped)");
  }
  if (header.abi_version != kAbiVersion) {
    throw ShmError(ShmErrc::kAbiMismatch,
                   "ABI mismatch on instance '" + seg.instance_ + "': the running core uses " +
                       "shared-memory ABI v" + std::to_string(header.abi_version) +
                       ", this program v" + std::to_string(kAbiVersion) +
                       "; rebuild so that all hapticctrl programs come from one version");
  }
  bool layout_ok = header.header_size == sizeof(SegmentHeader) &&
                   header.segment_size == kSegmentSize &&
                   static_cast<std::size_t>(st.st_size) == kSegmentSize;
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
    throw ShmError(ShmErrc::kNoController,
                   "no controller is running for instance '" + seg.instance_ + "': " + path +
                       " was left by core pid " + std::to_string(header.creator_pid) +
                       ", which is gone; the next core start replaces it");
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
                         " (one writer per region); stop that process first");
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
  if (creator_) {
    return true;
  }
  if (lock_fd_ < 0) {
    return false;
  }
  // A shared lock is only granted when no core holds the exclusive one; the kernel drops a
  // core's lock the moment its process ends, however it ends.
  if (flock(lock_fd_, LOCK_SH | LOCK_NB) == 0) {
    flock(lock_fd_, LOCK_UN);
    return false;
  }
  return errno == EWOULDBLOCK;
}

bool Segment::still_current() const {
  if (fd_ < 0 || header_->magic.load(std::memory_order_acquire) != kSegmentMagic) {
    return false;
  }
  struct stat mine {};
  struct stat named {};
  return fstat(fd_, &mine) == 0 && stat(shm_path(names_.segment).c_str(), &named) == 0 &&
         mine.st_ino == named.st_ino;
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
  if (creator_ && fd_ >= 0) {
    shm_unlink(names_.segment.c_str());
  }
  if (creator_ && lock_fd_ >= 0) {
    shm_unlink(names_.lock.c_str());  // while still holding the flock (see acquire_instance_lock)
  }
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (lock_fd_ >= 0) {
    ::close(lock_fd_);
    lock_fd_ = -1;
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
    names_ = std::move(other.names_);
    fd_ = std::exchange(other.fd_, -1);
    lock_fd_ = std::exchange(other.lock_fd_, -1);
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
