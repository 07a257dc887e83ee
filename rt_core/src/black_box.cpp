// Implements black_box.hpp: a preallocated ring of the last cycles' records, written out as CSV on
// fail-safe, so that the seconds before a fault can be examined afterwards (the flight-recorder of
// the core).
#include "hapticctrl/rt_core/black_box.hpp"

#include <stdexcept>

namespace hapticctrl::rt_core {

BlackBox::BlackBox(std::size_t capacity, shm::BlackBoxRing* mirror)
    : ring_(capacity == 0 ? 1 : capacity), mirror_(mirror) {}

void BlackBox::record(const CycleRecord& r) noexcept {
  ring_[count_ % ring_.size()] = r;
  ++count_;
  if (mirror_ != nullptr) {
    shm::push_cycle_record(*mirror_, r);
  }
}

const CycleRecord& BlackBox::at(std::size_t i) const noexcept {
  const std::size_t oldest = count_ < ring_.size() ? 0 : count_ % ring_.size();
  return ring_[(oldest + i) % ring_.size()];
}

std::string BlackBox::csv() const {
  std::vector<CycleRecord> records;
  records.reserve(size());
  for (std::size_t i = 0; i < size(); ++i) {
    records.push_back(at(i));
  }
  return shm::cycle_records_csv(records);
}

std::string store_black_box(const BlackBox& box, const PrivateDirectory& directory,
                            const std::string& instance, int pid, std::size_t keep) {
  // '.' cannot be in an instance's name: "lab"'s retention never takes "lab-2"'s black boxes.
  return directory.add_to_series("hapticctrl-blackbox-" + instance + ".", std::to_string(pid),
                                 ".csv", box.csv(), keep);
}

}  // namespace hapticctrl::rt_core
