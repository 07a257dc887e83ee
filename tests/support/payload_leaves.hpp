#pragma once
// Test support: a payload with one of its fields (a leaf of its table, payload_fields.hpp) set to
// a value none of the mappings would produce by chance, and the columns of the fields a mapping
// does not carry. The coverage tests of the LCM and DDS mappings are built on it.
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "hapticctrl/shm/payload_fields.hpp"

namespace hapticctrl::test {

/// The column names of P's leaves, in table order.
template <typename P>
std::vector<std::string> leaf_columns() {
  std::vector<std::string> out;
  const P p{};
  shm::for_each_leaf(
      p, [&](const std::string& column, const shm::Field&, const auto&) { out.push_back(column); });
  return out;
}

/// A default P with leaf `index` set: 0.75 for a double, 0x7FFFFF for an integer (in range of
/// every integer field, every flag of a bit word set, and a code no enum has).
template <typename P>
P with_leaf(std::size_t index) {
  P p{};
  std::size_t i = 0;
  shm::for_each_leaf(p, [&](const std::string&, const shm::Field&, auto& value) {
    using T = std::remove_reference_t<decltype(value)>;
    if (i++ == index) {
      value = std::is_floating_point_v<T> ? static_cast<T>(0.75) : static_cast<T>(0x7FFFFF);
    }
  });
  return p;
}

/// The columns of P whose change does (`carried`) or does not change `seen(p)` from what it is
/// with a default P.
template <typename P, typename Seen>
std::vector<std::string> columns_where(Seen seen, bool carried) {
  const auto columns = leaf_columns<P>();
  const auto baseline = seen(P{});
  std::vector<std::string> out;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if ((seen(with_leaf<P>(i)) != baseline) == carried) {
      out.push_back(columns[i]);
    }
  }
  return out;
}

/// What the mapping behind `seen` does not carry of P.
template <typename P, typename Seen>
std::vector<std::string> uncarried(Seen seen) {
  return columns_where<P>(seen, false);
}

/// What the mapping behind `seen` carries of P.
template <typename P, typename Seen>
std::vector<std::string> carried(Seen seen) {
  return columns_where<P>(seen, true);
}

}  // namespace hapticctrl::test
