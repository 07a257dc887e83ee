// Implements black_box_ring.hpp: the core's last cycles in the segment.
#include "hapticctrl/shm/black_box_ring.hpp"

#include <cstring>
#include <sstream>

namespace hapticctrl::shm {

void push_cycle_record(BlackBoxRing& ring, const CycleRecord& record) noexcept {
  const std::uint64_t index = ring.head.load(std::memory_order_relaxed);
  BlackBoxSlot& slot = ring.slots[index % kBlackBoxSlots];
  // The seqlock's argument (seqlock.hpp): a reader whose acquire load sees a word of this write
  // synchronises with its release store, sequenced after the zero stamp, so its re-check of the
  // stamp cannot see the old one; no fence (ThreadSanitizer does not model fences).
  slot.stamp.store(0, std::memory_order_relaxed);  // being rewritten: a reader leaves it out
  std::array<std::uint64_t, kRecordWords> words{};
  std::memcpy(words.data(), &record, sizeof(record));
  for (std::size_t i = 0; i < kRecordWords; ++i) {
    slot.words[i].store(words[i], std::memory_order_release);
  }
  slot.stamp.store(index + 1, std::memory_order_release);
  ring.head.store(index + 1, std::memory_order_release);
}

std::vector<CycleRecord> read_cycle_records(const BlackBoxRing& ring) {
  const std::uint64_t head = ring.head.load(std::memory_order_acquire);
  const std::uint64_t first = head > kBlackBoxSlots ? head - kBlackBoxSlots : 0;
  std::vector<CycleRecord> records;
  records.reserve(static_cast<std::size_t>(head - first));
  for (std::uint64_t index = first; index < head; ++index) {
    const BlackBoxSlot& slot = ring.slots[index % kBlackBoxSlots];
    if (slot.stamp.load(std::memory_order_acquire) != index + 1) {
      continue;  // overwritten since head was read
    }
    std::array<std::uint64_t, kRecordWords> words{};
    for (std::size_t i = 0; i < kRecordWords; ++i) {
      words[i] = slot.words[i].load(std::memory_order_acquire);
    }
    if (slot.stamp.load(std::memory_order_relaxed) != index + 1) {
      continue;  // the writer came round while it was copied
    }
    CycleRecord r;
    std::memcpy(static_cast<void*>(&r), words.data(), sizeof(r));
    records.push_back(r);
  }
  return records;
}

std::string cycle_records_csv(const std::vector<CycleRecord>& records) {
  std::ostringstream out;
  out << "cycle,scheduled_ns,wake_latency_ns,servo_start_delay_ns,servo_execution_ns,miss,"
         "degraded,stall,skipped,consecutive_misses,state_word";
  for (int j = 1; j <= 6; ++j) {
    out << ",q" << j;
  }
  for (int j = 1; j <= 6; ++j) {
    out << ",tau" << j;
  }
  out << "\n";
  for (const CycleRecord& r : records) {
    out << r.cycle << ',' << r.scheduled << ',' << r.wake_latency << ',' << r.servo_start_delay
        << ',' << r.servo_execution << ',' << ((r.flags & kRecordMiss) ? 1 : 0) << ','
        << ((r.flags & kRecordDegraded) ? 1 : 0) << ',' << ((r.flags & kRecordStall) ? 1 : 0) << ','
        << r.skipped << ',' << r.consecutive_misses << ',' << r.state_word;
    for (const double q : r.joint_position) {
      out << ',' << q;
    }
    for (const double t : r.joint_torque) {
      out << ',' << t;
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace hapticctrl::shm
