#pragma once
/// The regions of one instance in ordinary memory, for tests of the servo and the executive
/// that do not need a shared-memory segment.

#include <memory>

#include "hapticctrl/rt_core/servo.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::test {

template <typename T>
using CellPtr = std::unique_ptr<shm::SeqlockCell<T>>;

struct InMemoryRegions {
  std::unique_ptr<shm::CtrlRegion> ctrl = std::make_unique<shm::CtrlRegion>();
  std::unique_ptr<shm::CtrlAckRegion> acks = std::make_unique<shm::CtrlAckRegion>();
  CellPtr<shm::VprPayload> vpr = std::make_unique<shm::SeqlockCell<shm::VprPayload>>();
  CellPtr<shm::VpPayload> vp = std::make_unique<shm::SeqlockCell<shm::VpPayload>>();
  CellPtr<shm::PositionPayload> position =
      std::make_unique<shm::SeqlockCell<shm::PositionPayload>>();
  CellPtr<shm::TelemetryPayload> telemetry =
      std::make_unique<shm::SeqlockCell<shm::TelemetryPayload>>();
  CellPtr<shm::ForcePayload> force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();

  [[nodiscard]] shm::CtrlReader ctrl_reader() const { return {*ctrl, *acks}; }
  [[nodiscard]] shm::CtrlWriter ctrl_writer(std::size_t slot = 0) const {
    return {ctrl->slots[slot], acks->slots[slot], slot};
  }
  [[nodiscard]] rt_core::ServoRegions servo_regions() const {
    return {vpr.get(), vp.get(), position.get()};
  }
};

}  // namespace hapticctrl::test
