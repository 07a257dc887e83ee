#pragma once
/// The controller side of the UDP bridge's session in ordinary memory: real VPr and ctrl cells
/// (no segment, no core), for the session tests and the fuzz target.
#include <atomic>
#include <memory>
#include <vector>

#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"
#include "hapticctrl/udp_bridge/session.hpp"

namespace hapticctrl::test {

struct InMemoryController {
  std::unique_ptr<shm::SeqlockCell<shm::VprPayload>> vpr =
      std::make_unique<shm::SeqlockCell<shm::VprPayload>>();
  std::unique_ptr<shm::CtrlRegion> ctrl = std::make_unique<shm::CtrlRegion>();
  std::unique_ptr<shm::CtrlAckRegion> acks = std::make_unique<shm::CtrlAckRegion>();
  shm::CtrlWriter writer{ctrl->slots[0], acks->slots[0], 0};
  std::unique_ptr<std::atomic<std::uint64_t>> cycle =
      std::make_unique<std::atomic<std::uint64_t>>(0);  ///< the core's heartbeat
  udp_bridge::ControllerPorts ports{vpr.get(), &writer, std::chrono::milliseconds(1), cycle.get()};

  /// The last VPr sample (default-constructed if none was published).
  [[nodiscard]] shm::VprPayload vpr_now() const {
    shm::VprPayload v;
    vpr->read(v);
    return v;
  }
  /// How many VPr samples were published so far.
  [[nodiscard]] std::uint64_t vpr_publishes() const {
    shm::VprPayload v;
    return vpr->read(v).sequence;
  }
  /// Consumes the queued ctrl commands, as the core would.
  std::vector<shm::CtrlCode> drain() {
    std::vector<shm::CtrlCode> codes;
    shm::CtrlReader(*ctrl, *acks).drain([&](const shm::CtrlCommand& c) {
      codes.push_back(c.code);
      return true;
    });
    return codes;
  }
};

}  // namespace hapticctrl::test
