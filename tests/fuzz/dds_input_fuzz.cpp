// libFuzzer target: the DDS bridge's input as Cyclone DDS hands it over after decoding: commands
// (std_msgs/String of any length and any bytes) and operator wrenches (geometry_msgs/
// WrenchStamped with any six doubles: NaN, +-inf, 1e308, denormals), with remote commands enabled
// so that every path runs, into real in-memory ctrl and force cells (the path of
// bridges/dds/src/main.cpp). After each input the force the bridge publishes must still be
// finite and within the operator limits, whatever arrived.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include "hapticctrl/dds_bridge/commands.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/remote_commands.hpp"
#include "support/in_memory_controller.hpp"

namespace {

namespace db = hapticctrl::dds_bridge;
namespace shm = hapticctrl::shm;

struct Harness {
  hapticctrl::test::InMemoryController controller;
  std::unique_ptr<shm::SeqlockCell<shm::ForcePayload>> force =
      std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  shm::RemoteCommands remote{shm::RemoteCommandSettings{true, {}, std::chrono::milliseconds(200)},
                             &controller.writer, force.get()};
  hapticctrl::TimePoint now;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Harness h;
  if (size == 0) {
    return 0;
  }
  // First byte: which topic, and how far the clock moves (up to 127 ms).
  h.now += std::chrono::milliseconds(data[0] >> 1U);
  if ((data[0] & 1U) != 0) {
    // A string as DDS delivers it: NUL-terminated, any bytes before (a NUL inside ends it).
    std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
    std_msgs_msg_dds__String_ message{};
    message.data_ = text.data();
    h.remote.command(db::command_of(message), h.now);
  } else {
    geometry_msgs_msg_dds__WrenchStamped_ message{};
    double values[6] = {};  // NOLINT(*-avoid-c-arrays): as the bytes arrive
    std::memcpy(values, data + 1, std::min(sizeof(values), size - 1));
    message.wrench_.force_ = {values[0], values[1], values[2]};
    message.wrench_.torque_ = {values[3], values[4], values[5]};
    h.remote.force(db::wrench_of(message), h.now);
  }
  h.remote.tick(h.now);
  (void)h.controller.drain();  // the core's side, so that the ctrl ring never fills for good
  shm::ForcePayload out;
  if (h.force->read(out).ok() && !shm::wrench_acceptable(out.wrench)) {
    __builtin_trap();  // the bridge published a force the core would refuse
  }
  return 0;
}
