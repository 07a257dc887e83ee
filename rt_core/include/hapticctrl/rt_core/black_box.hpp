#pragma once
/// @file black_box.hpp
/// A preallocated ring of the last cycles' records, written out as CSV on fail-safe, so that
/// the seconds before a fault can be examined afterwards (the flight-recorder of the core).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/program/private_directory.hpp"
#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/shm/black_box_ring.hpp"

namespace hapticctrl::rt_core {

using program::PrivateDirectory;

using shm::CycleRecord;  // the record, the region and the CSV format are the segment's contract
using shm::kRecordDegraded;
using shm::kRecordMiss;
using shm::kRecordStall;

class BlackBox {
 public:
  /// Allocates room for `capacity` records (setup; the ring never allocates afterwards). Each
  /// record also goes into `mirror` (the segment's blackbox region) unless it is null, so that
  /// a killed core leaves its last cycles to whoever maps the segment.
  explicit BlackBox(std::size_t capacity, shm::BlackBoxRing* mirror = nullptr);

  /// Real-time contract: safe in the cycle (copies into the preallocated rings; no syscall).
  HAPTICCTRL_RT void record(const CycleRecord& r) noexcept;

  [[nodiscard]] std::size_t size() const noexcept {
    return count_ < ring_.size() ? count_ : ring_.size();
  }
  [[nodiscard]] std::size_t capacity() const noexcept { return ring_.size(); }
  /// The i-th oldest record still held (0 = oldest).
  [[nodiscard]] const CycleRecord& at(std::size_t i) const noexcept;

  /// The records oldest first as CSV text. Not for the cycle (allocates).
  [[nodiscard]] std::string csv() const;

 private:
  std::vector<CycleRecord> ring_;
  std::size_t count_ = 0;
  shm::BlackBoxRing* mirror_ = nullptr;
};

/// Writes `box` into `directory` as `hapticctrl-blackbox-<instance>.<pid>.csv` (a name already
/// there, a link included, is left alone: `.2`, `.3`, ... is appended), created exclusively with
/// mode 0600, then removes the instance's oldest black boxes there beyond `keep` (at least the
/// new one stays). Returns the new file's path. Not for the cycle; throws std::runtime_error.
std::string store_black_box(const BlackBox& box, const PrivateDirectory& directory,
                            const std::string& instance, int pid, std::size_t keep);

}  // namespace hapticctrl::rt_core
