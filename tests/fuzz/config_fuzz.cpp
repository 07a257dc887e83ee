// libFuzzer target: every command line and text the programs parse before they start: the
// core's, the three bridges', the HMI's and the demo's options, client addresses and operator force
// sequences. The first byte chooses the parser; the rest is split at newlines into arguments
// (the sequence parser gets it whole). Each parser must return or throw its documented
// exception with a message; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/demo/demo_options.hpp"
#include "hapticctrl/hmi/hmi_options.hpp"
#include "hapticctrl/hmi/wrench_sequence.hpp"
#include "hapticctrl/lcm_bridge/lcm_bridge_config.hpp"
#include "hapticctrl/rt_core/core_config.hpp"
#include "hapticctrl/udp_bridge/bridge_config.hpp"
#include "hapticctrl/web_bridge/web_config.hpp"

namespace {

std::vector<std::string> arguments(const std::string& text) {
  std::vector<std::string> args;
  std::size_t start = 0;
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', start)) {
    args.push_back(text.substr(start, at - start));
    start = at + 1;
  }
  args.push_back(text.substr(start));
  return args;
}

void parse(std::uint8_t which, const std::string& text) {
  switch (which % 8) {
    case 0:
      (void)hapticctrl::rt_core::parse_core_args(arguments(text));
      break;
    case 1:
      (void)hapticctrl::udp_bridge::BridgeConfig::parse(arguments(text));
      break;
    case 2:
      (void)hapticctrl::lcm_bridge::LcmBridgeConfig::parse(arguments(text));
      break;
    case 3:
      (void)hapticctrl::hmi::HmiOptions::parse(arguments(text));
      break;
    case 4:
      (void)hapticctrl::demo::DemoOptions::parse(arguments(text));
      break;
    case 5:
      (void)hapticctrl::client::Address::parse(text);
      break;
    case 6:
      (void)hapticctrl::web_bridge::WebConfig::parse(arguments(text));
      break;
    default:
      (void)hapticctrl::hmi::WrenchSequence::parse(text, "fuzz");
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  try {
    parse(data[0], std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  } catch (const std::invalid_argument&) {
    // every option parser's refusal
  } catch (const hapticctrl::client::ClientError&) {
    // Address::parse's refusal (kInvalidArgument)
  }
  return 0;
}
