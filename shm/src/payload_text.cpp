// Implements payload_text.hpp: a payload's CSV columns and JSON object from its field table.
#include "hapticctrl/shm/payload_text.hpp"

#include <arpa/inet.h>

#include <cmath>
#include <cstring>
#include <sstream>

namespace hapticctrl::shm {
namespace {

/// Writes one value: integers as integers, doubles with 9 significant digits, null for what
/// JSON cannot carry ("-nan" made a whole status document unreadable, 2026-12-03), an "ipv4"
/// field as dotted text.
template <typename T>
void write_value(std::ostringstream& out, const Field& f, T value, bool quote_text) {
  if constexpr (std::is_floating_point_v<T>) {
    if (std::isfinite(value)) {
      out << value;
    } else {
      out << (quote_text ? "null" : "");
    }
  } else if (std::strcmp(f.unit, "ipv4") == 0) {
    const std::string text = ipv4_text(static_cast<std::uint32_t>(value));
    out << (quote_text ? "\"" : "") << text << (quote_text ? "\"" : "");
  } else {
    out << +value;  // + : a uint8_t would print as a character
  }
}

template <typename T>
void write_json(std::ostringstream& out, const Field& f, const T& value) {
  if constexpr (kNested<T>) {
    out << '{';
    const char* sep = "";
    for_each_field(value, [&](const Field& inner, const auto& v) {
      out << sep << '"' << inner.name << "\":";
      write_json(out, inner, v);
      sep = ",";
    });
    out << '}';
  } else if constexpr (std::is_arithmetic_v<T>) {
    write_value(out, f, value, true);
  } else {
    out << '[';
    for (std::size_t i = 0; i < value.size(); ++i) {
      out << (i == 0 ? "" : ",");
      write_json(out, f, value[i]);
    }
    out << ']';
  }
}

}  // namespace

std::string ipv4_text(std::uint32_t host_order) {
  in_addr a{};
  a.s_addr = htonl(host_order);
  char text[INET_ADDRSTRLEN] = {};  // NOLINT(*-avoid-c-arrays): inet_ntop's buffer
  ::inet_ntop(AF_INET, &a, text, sizeof text);
  return text;
}

template <Described P>
std::string csv_header() {
  std::string out;
  const P p{};
  for_each_leaf(p, [&](const std::string& column, const Field&, const auto&) {
    out += (out.empty() ? "" : ",") + column;
  });
  return out;
}

template <Described P>
std::string csv_row(const P& p) {
  std::ostringstream out;
  out.precision(9);
  const char* sep = "";
  for_each_leaf(p, [&](const std::string&, const Field& f, const auto& value) {
    out << sep;
    write_value(out, f, value, false);
    sep = ",";
  });
  return out.str();
}

template <Described P>
std::string fields_json(const P& p) {
  std::ostringstream out;
  out.precision(9);
  write_json(out, Field{"", "", ""}, p);
  return out.str();
}

#define HAPTICCTRL_PAYLOAD_TEXT(P)        \
  template std::string csv_header<P>();   \
  template std::string csv_row(const P&); \
  template std::string fields_json(const P&);
HAPTICCTRL_PAYLOAD_TEXT(VprPayload)
HAPTICCTRL_PAYLOAD_TEXT(VpPayload)
HAPTICCTRL_PAYLOAD_TEXT(ForcePayload)
HAPTICCTRL_PAYLOAD_TEXT(PositionPayload)
HAPTICCTRL_PAYLOAD_TEXT(TelemetryPayload)
HAPTICCTRL_PAYLOAD_TEXT(LinkStatsPayload)
#undef HAPTICCTRL_PAYLOAD_TEXT

}  // namespace hapticctrl::shm
