// Implements black_box.hpp: a preallocated ring of the last cycles' records, written out as CSV on
// fail-safe, so that the seconds before a fault can be examined afterwards (the flight-recorder of
// the core).
#include "hapticctrl/rt_core/black_box.hpp"

#include <fstream>
#include <stdexcept>

namespace hapticctrl::rt_core {

BlackBox::BlackBox(std::size_t capacity) : ring_(capacity == 0 ? 1 : capacity) {}

void BlackBox::record(const CycleRecord& r) noexcept {
  ring_[count_ % ring_.size()] = r;
  ++count_;
}

const CycleRecord& BlackBox::at(std::size_t i) const noexcept {
  const std::size_t oldest = count_ < ring_.size() ? 0 : count_ % ring_.size();
  return ring_[(oldest + i) % ring_.size()];
}

void BlackBox::write_csv(const std::string& path) const {
  std::ofstream out(path);
  if (!out) {
    throw std::runtime_error("cannot write black box to '" + path + "'");
  }
  out << "cycle,scheduled_ns,wake_latency_ns,servo_start_delay_ns,servo_execution_ns,miss,"
         "degraded,stall,skipped,consecutive_misses,state_word";
  for (int j = 1; j <= 6; ++j) {
    out << ",q" << j;
  }
  for (int j = 1; j <= 6; ++j) {
    out << ",tau" << j;
  }
  out << "\n";
  for (std::size_t i = 0; i < size(); ++i) {
    const CycleRecord& r = at(i);
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
  if (!out) {
    throw std::runtime_error("error while writing black box '" + path + "'");
  }
}

}  // namespace hapticctrl::rt_core
