#pragma once
/// @file payload_text.hpp
/// A region payload as text, driven by its field table (payload_fields.hpp): one CSV header and
/// row per payload (columns "<field>_<part>", nested structs unrolled) and a JSON object (arrays
/// as arrays, nested structs as objects). Numbers JSON cannot carry (NaN, infinities) are null;
/// a field whose unit is "ipv4" is written as dotted text.
///
/// Real-time contract: not for the cycle (allocates).

#include <cstdint>
#include <string>

#include "hapticctrl/shm/payload_fields.hpp"

namespace hapticctrl::shm {

/// The CSV header of `P`'s columns, comma-separated, no newline.
template <Described P>
[[nodiscard]] std::string csv_header();

/// The values of `p` in csv_header<P>()'s order, comma-separated, no newline.
template <Described P>
[[nodiscard]] std::string csv_row(const P& p);

/// `p` as one JSON object keyed by field name.
template <Described P>
[[nodiscard]] std::string fields_json(const P& p);

/// An IPv4 address held in host byte order (link_stats' peer_ipv4) as dotted text.
[[nodiscard]] std::string ipv4_text(std::uint32_t host_order);

}  // namespace hapticctrl::shm
