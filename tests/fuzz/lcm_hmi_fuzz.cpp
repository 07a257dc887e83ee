// libFuzzer target: LCM HMI traffic as the LCM bridge receives it (hmi_command_t and
// hmi_force_t, any bytes), with remote commands enabled so that every path runs, into real
// in-memory ctrl and force cells. After each input the force the bridge publishes must still be
// finite and within the operator limits, whatever arrived.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "hapticctrl/lcm_bridge/hmi_input.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "support/in_memory_controller.hpp"

namespace {

namespace lb = hapticctrl::lcm_bridge;
namespace shm = hapticctrl::shm;

struct Harness {
  hapticctrl::test::InMemoryController controller;
  std::unique_ptr<shm::SeqlockCell<shm::ForcePayload>> force =
      std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  lb::HmiInput input{lb::HmiSettings{true}, &controller.writer, force.get()};
  hapticctrl::TimePoint now;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Harness h;
  if (size == 0) {
    return 0;
  }
  // First byte: which channel, and how far the clock moves (up to 255 ms).
  h.now += std::chrono::milliseconds(data[0]);
  if ((data[0] & 1U) != 0) {
    h.input.on_command(data + 1, size - 1, h.now);
  } else {
    h.input.on_force(data + 1, size - 1, h.now);
  }
  h.input.tick(h.now);
  (void)h.controller.drain();  // the core's side, so that the ctrl ring never fills for good
  shm::ForcePayload out;
  if (h.force->read(out).ok() && !shm::wrench_acceptable(out.wrench)) {
    __builtin_trap();  // the bridge published a force the core would refuse
  }
  return 0;
}
