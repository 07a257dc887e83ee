// Implements black_box.hpp: a preallocated ring of the last cycles' records, written out as CSV on
// fail-safe, so that the seconds before a fault can be examined afterwards (the flight-recorder of
// the core).
#include "hapticctrl/rt_core/black_box.hpp"

#include <sstream>
#include <stdexcept>

namespace hapticctrl::rt_core {
namespace {

/// Names tried for one black box: the pid's, then -2 ... (a pid the state directory saw before).
constexpr int kNameAttempts = 100;

}  // namespace

BlackBox::BlackBox(std::size_t capacity) : ring_(capacity == 0 ? 1 : capacity) {}

void BlackBox::record(const CycleRecord& r) noexcept {
  ring_[count_ % ring_.size()] = r;
  ++count_;
}

const CycleRecord& BlackBox::at(std::size_t i) const noexcept {
  const std::size_t oldest = count_ < ring_.size() ? 0 : count_ % ring_.size();
  return ring_[(oldest + i) % ring_.size()];
}

std::string BlackBox::csv() const {
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
  return out.str();
}

std::string store_black_box(const BlackBox& box, const PrivateDirectory& directory,
                            const std::string& instance, int pid, std::size_t keep) {
  // '.' cannot be in an instance's name: "lab"'s retention never takes "lab-2"'s black boxes.
  const std::string prefix = "hapticctrl-blackbox-" + instance + ".";
  const std::string text = box.csv();
  std::string written;
  for (int n = 1; n <= kNameAttempts && written.empty(); ++n) {
    const std::string name =
        prefix + std::to_string(pid) + (n == 1 ? "" : "." + std::to_string(n)) + ".csv";
    if (directory.create_file(name, text)) {
      written = name;
    }
  }
  if (written.empty()) {
    throw std::runtime_error("no free black-box name in " + directory.path() + " for " + prefix +
                             std::to_string(pid) + " after " + std::to_string(kNameAttempts) +
                             " tries");
  }
  std::vector<std::string> kept = directory.files(prefix, ".csv");
  std::erase(kept, written);  // the new one stays whatever its time stamp
  const std::size_t others = keep > 0 ? keep - 1 : 0;
  for (std::size_t i = 0; i + others < kept.size(); ++i) {
    directory.remove(kept[i]);
  }
  return directory.path() + "/" + written;
}

}  // namespace hapticctrl::rt_core
