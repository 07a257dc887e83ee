// Tests of udp_socket.hpp: the datagram transport seam shared by the UDP bridge and the client
// library, and its UDP/IPv4 implementation.
#include "hapticctrl/protocol/udp_socket.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace hapticctrl::protocol {
namespace {

using namespace std::chrono_literals;

TEST(UdpSocket, LoopbackDatagramRoundTrip) {
  UdpSocket a(Endpoint::resolve("127.0.0.1", 0));
  UdpSocket b(Endpoint::resolve("127.0.0.1", 0));
  const std::array<std::uint8_t, 4> out{1, 2, 3, 4};
  ASSERT_TRUE(a.send_to(out, b.local_endpoint()));
  std::array<std::uint8_t, 16> in{};
  Endpoint from;
  const Received r = b.receive(in, from, 1s);
  ASSERT_EQ(r.status, Received::Status::kDatagram);
  EXPECT_EQ(r.size, 4U);
  EXPECT_EQ(in[3], 4);
  EXPECT_EQ(from, a.local_endpoint());
  EXPECT_TRUE(from.is_loopback());
}

TEST(UdpSocket, TimesOutWhenNothingArrives) {
  UdpSocket s(Endpoint::resolve("127.0.0.1", 0));
  std::array<std::uint8_t, 16> in{};
  Endpoint from;
  EXPECT_EQ(s.receive(in, from, 5ms).status, Received::Status::kTimeout);
  EXPECT_EQ(s.receive(in, from, 0ns).status, Received::Status::kTimeout);
}

TEST(UdpSocket, OversizedDatagramsAreConsumedAndReported) {
  UdpSocket a(Endpoint::resolve("127.0.0.1", 0));
  UdpSocket b(Endpoint::resolve("127.0.0.1", 0));
  const std::vector<std::uint8_t> big(2000, 7);
  ASSERT_TRUE(a.send_to(big, b.local_endpoint()));
  ASSERT_TRUE(a.send_to(std::vector<std::uint8_t>(8, 1), b.local_endpoint()));
  std::array<std::uint8_t, 512> in{};
  Endpoint from;
  EXPECT_EQ(b.receive(in, from, 1s).status, Received::Status::kOversized);
  const Received next = b.receive(in, from, 1s);  // the next datagram is intact
  EXPECT_EQ(next.status, Received::Status::kDatagram);
  EXPECT_EQ(next.size, 8U);
}

TEST(UdpSocket, SetupErrorsSayWhat) {
  UdpSocket a(Endpoint::resolve("127.0.0.1", 0));
  try {
    UdpSocket clash(a.local_endpoint());
    FAIL() << "binding a used port must fail";
  } catch (const std::system_error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr(a.local_endpoint().to_string()));
  }
  EXPECT_THROW((void)Endpoint::resolve("no-such-host.invalid", 1), std::invalid_argument);
  EXPECT_EQ(Endpoint::resolve("localhost", 5125).to_string(), "127.0.0.1:5125");
}

}  // namespace
}  // namespace hapticctrl::protocol
