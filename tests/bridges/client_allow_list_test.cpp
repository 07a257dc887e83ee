// Tests of client_allow_list.hpp: which client addresses the UDP bridge serves (--allow-client):
// IPv4 networks, each an address with an optional prefix length.
#include "hapticctrl/udp_bridge/client_allow_list.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::udp_bridge {
namespace {

constexpr std::uint32_t ip(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  return a << 24U | b << 16U | c << 8U | d;
}

TEST(ClientAllowList, AnEmptyListAllowsEveryAddress) {
  EXPECT_TRUE(ClientAllowList().allows(ip(203, 0, 113, 9)));
}

TEST(ClientAllowList, AddressesAndNetworksAllowExactlyTheirMembers) {
  const ClientAllowList list({Ipv4Network::parse("127.0.0.1"), Ipv4Network::parse("10.1.0.0/16")});
  EXPECT_TRUE(list.allows(ip(127, 0, 0, 1)));
  EXPECT_FALSE(list.allows(ip(127, 0, 0, 2)));
  EXPECT_TRUE(list.allows(ip(10, 1, 255, 7)));
  EXPECT_FALSE(list.allows(ip(10, 2, 0, 1)));
}

TEST(ClientAllowList, PrefixZeroIsEveryAddressAndTheHostBitsOfANetworkDoNotMatter) {
  EXPECT_TRUE(ClientAllowList({Ipv4Network::parse("0.0.0.0/0")}).allows(ip(8, 8, 8, 8)));
  EXPECT_TRUE(ClientAllowList({Ipv4Network::parse("192.168.1.77/24")}).allows(ip(192, 168, 1, 3)));
}

TEST(ClientAllowList, WhatIsNotAnIpv4NetworkIsRefusedByName) {
  for (const char* bad : {"", "lab-pc", "1.2.3", "1.2.3.4/", "1.2.3.4/x", "1.2.3.4/33", "::1"}) {
    EXPECT_THROW(Ipv4Network::parse(bad), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
