// libFuzzer target: every datagram the UDP bridge can receive, through the codec and the
// session state machine (with real in-memory VPr and ctrl cells). Runs in CI for a bounded time
// (scripts/test.sh). Half of the inputs get a correct CRC appended, so that the fuzzer reaches
// XDR decoding, value checks and the session instead of stopping at the checksum.
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/udp_bridge/session.hpp"
#include "support/in_memory_controller.hpp"

namespace {

using hapticctrl::protocol::Endpoint;
using hapticctrl::protocol::FrameBuffer;
namespace shm = hapticctrl::shm;

struct Harness {
  hapticctrl::test::InMemoryController controller;
  // The golden tests' token, so that seeds and mutations can carry a valid one.
  hapticctrl::udp_bridge::Session session{{100}, [] { return 0x0102030405060708ULL; }};
  Endpoint peer = Endpoint::resolve("127.0.0.1", 40000);
  hapticctrl::TimePoint now;

  Harness() { session.set_controller(&controller.ports, hapticctrl::TimePoint{}); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Harness h;
  std::vector<std::uint8_t> bytes(data, data + size);
  if (size > 0 && (data[0] & 1U) != 0 && size >= 4) {
    const auto crc = static_cast<std::uint32_t>(::crc32(0UL, data, static_cast<uInt>(size - 4)));
    for (std::size_t i = 0; i < 4; ++i) {
      bytes[size - 4 + i] = static_cast<std::uint8_t>(crc >> (24U - 8U * i));
    }
  }
  hcp_frame frame;
  (void)hapticctrl::protocol::decode(bytes, frame);
  FrameBuffer reply{};
  h.now += std::chrono::milliseconds(1);
  (void)h.session.on_datagram(bytes, h.peer, h.now, reply);
  h.session.check_watchdog(h.now);
  h.controller.drain();
  return 0;
}
