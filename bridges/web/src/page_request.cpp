// Implements page_request.hpp: what a page may ask, validated: JSON text from a WebSocket becomes
// an HMI command or an operator wrench for LCM (hmi_command_t, hmi_force_t), or a refusal with its
// reason.
#include "hapticctrl/web_bridge/page_request.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "hapticctrl_lcm/hmi_command_t.hpp"

namespace hapticctrl::web_bridge {
namespace {

using Json = nlohmann::json;
using Command = hapticctrl_lcm::hmi_command_t;

PageRequest refusal(PageRequestKind kind, std::string name, std::string reason) {
  PageRequest r;
  r.kind = kind;
  r.name = std::move(name);
  r.reason = std::move(reason);
  return r;
}

/// The hmi_command_t code of a command name; 0 when unknown.
std::int32_t command_code(const std::string& name) {
  if (name == "power_on") {
    return Command::POWER_ON;
  }
  if (name == "power_off") {
    return Command::POWER_OFF;
  }
  if (name == "emergency_stop") {
    return Command::EMERGENCY_STOP;
  }
  if (name == "emergency_reset") {
    return Command::EMERGENCY_RESET;
  }
  return 0;
}

PageRequest command_request(const Json& message, bool allow_remote_commands) {
  const auto it = message.find("command");
  if (it == message.end() || !it->is_string()) {
    return refusal(PageRequestKind::kMalformed, "command", "a command needs a \"command\" name");
  }
  const std::string name = it->get<std::string>();
  const std::int32_t code = command_code(name);
  if (code == 0) {
    return refusal(PageRequestKind::kMalformed, name.substr(0, 40), "unknown command");
  }
  if (code != Command::EMERGENCY_STOP && !allow_remote_commands) {
    return refusal(PageRequestKind::kRefused, name,
                   "remote commands are disabled (hapticctrl-web --allow-remote-commands)");
  }
  PageRequest r;
  r.kind = PageRequestKind::kCommand;
  r.command = code;
  r.name = name;
  return r;
}

PageRequest force_request(const Json& message, bool allow_remote_commands) {
  const auto it = message.find("wrench");
  if (it == message.end() || !it->is_array() || it->size() != 6) {
    return refusal(PageRequestKind::kMalformed, "force", "a force needs \"wrench\": six numbers");
  }
  PageRequest r;
  r.name = "force";
  for (std::size_t i = 0; i < 6; ++i) {
    const Json& v = (*it)[i];
    if (!v.is_number()) {
      return refusal(PageRequestKind::kMalformed, "force", "a force needs \"wrench\": six numbers");
    }
    r.wrench[i] = v.get<double>();
    const double bound = i < 3 ? kMaxPageForce : kMaxPageTorque;
    if (!std::isfinite(r.wrench[i]) || std::fabs(r.wrench[i]) > bound) {
      return refusal(PageRequestKind::kOutOfRange, "force",
                     "wrench values must be finite, within 100 N and 10 N.m per axis");
    }
  }
  if (!allow_remote_commands) {
    return refusal(PageRequestKind::kRefused, "force",
                   "remote commands are disabled (hapticctrl-web --allow-remote-commands)");
  }
  r.kind = PageRequestKind::kForce;
  return r;
}

}  // namespace

PageRequest parse_page_request(std::string_view text, bool allow_remote_commands) {
  if (text.size() > kMaxPageMessageBytes) {
    return refusal(PageRequestKind::kMalformed, "", "message too long");
  }
  // No exceptions (a malformed text is an ordinary input here), no depth bomb: the size bound
  // above keeps nlohmann's recursion shallow (1 KiB: at most 1024 levels).
  const Json message = Json::parse(text.begin(), text.end(), nullptr, false);
  if (message.is_discarded() || !message.is_object()) {
    return refusal(PageRequestKind::kMalformed, "", "not a JSON object");
  }
  const auto type = message.find("type");
  if (type == message.end() || !type->is_string()) {
    return refusal(PageRequestKind::kMalformed, "", "no \"type\"");
  }
  if (*type == "command") {
    return command_request(message, allow_remote_commands);
  }
  if (*type == "force") {
    return force_request(message, allow_remote_commands);
  }
  return refusal(PageRequestKind::kMalformed, "", "unknown type");
}

std::string reply_json(const std::string& request, bool ok, const std::string& reason) {
  Json reply{{"type", "reply"}, {"request", request}, {"ok", ok}};
  if (!ok) {
    reply["reason"] = reason;
  }
  // Replace: a name cut inside a UTF-8 sequence must not make dump() throw.
  return reply.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string reply_json(const PageRequest& request) {
  return reply_json(request.name, request.accepted(), request.reason);
}

}  // namespace hapticctrl::web_bridge
