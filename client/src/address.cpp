// Address::parse: the controller addresses a client accepts (udpxdr://host:port, host#port).
#include <charconv>
#include <string>
#include <string_view>

#include "hapticctrl/client/connection.hpp"

namespace hapticctrl::client {

Address Address::parse(std::string_view text) {
  std::string_view rest = text;
  constexpr std::string_view kScheme = "udpxdr://";
  if (rest.substr(0, kScheme.size()) == kScheme) {
    rest.remove_prefix(kScheme.size());
  }
  Address a;
  const std::size_t sep = rest.find_last_of("#:");
  a.host = std::string(rest.substr(0, sep));
  if (sep != std::string_view::npos) {
    const std::string_view port = rest.substr(sep + 1);
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (ec != std::errc{} || end != port.data() + port.size() || value == 0 || value > 65535) {
      throw ClientError(ErrorCode::kInvalidArgument,
                        "bad controller address '" + std::string(text) +
                            "': expected udpxdr://host:port or host#port with a port 1-65535");
    }
    a.port = static_cast<std::uint16_t>(value);
  }
  if (a.host.empty()) {
    throw ClientError(ErrorCode::kInvalidArgument,
                      "bad controller address '" + std::string(text) + "': no host");
  }
  return a;
}

}  // namespace hapticctrl::client
