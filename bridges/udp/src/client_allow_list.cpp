// Implements client_allow_list.hpp: which client addresses the UDP bridge serves (--allow-client):
// IPv4 networks, each an address with an optional prefix length.
#include "hapticctrl/udp_bridge/client_allow_list.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <stdexcept>

namespace hapticctrl::udp_bridge {

Ipv4Network Ipv4Network::parse(const std::string& text) {
  const auto slash = text.find('/');
  const std::string address = text.substr(0, slash);
  in_addr a{};
  if (::inet_pton(AF_INET, address.c_str(), &a) != 1) {
    throw std::invalid_argument("'" + text + "' is not an IPv4 address (a.b.c.d or a.b.c.d/n)");
  }
  unsigned prefix = 32;
  if (slash != std::string::npos) {
    const char* first = text.data() + slash + 1;
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, prefix);
    if (ec != std::errc{} || end != last || first == last || prefix > 32) {
      throw std::invalid_argument("'" + text + "': the prefix length must be 0..32");
    }
  }
  Ipv4Network n;
  n.address = ntohl(a.s_addr);
  n.mask = prefix == 0 ? 0U : 0xFFFFFFFFU << (32U - prefix);
  return n;
}

}  // namespace hapticctrl::udp_bridge
