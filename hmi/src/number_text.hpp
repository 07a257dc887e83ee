#pragma once
// The HMI's one way to read a number from text (command line, sequence files).
#include <cmath>
#include <string>

namespace hapticctrl::hmi {

/// Parses all of `text` as a finite number. False (and `out` unspecified) otherwise.
inline bool parse_finite(const std::string& text, double& out) {
  std::size_t used = 0;
  try {
    out = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && std::isfinite(out);
}

}  // namespace hapticctrl::hmi
