#pragma once
/// @file log_csv.hpp
/// Offline analysis: an LCM log (lcm-logger) to one CSV file per hapticctrl channel.
/// Not real-time code: it allocates and does file I/O.
#include <cstdint>
#include <map>
#include <string>

namespace hapticctrl::lcm_bridge {

struct CsvReport {
  std::map<std::string, std::uint64_t> rows;  ///< per written file name
  std::uint64_t skipped = 0;                  ///< events of other channels
  std::uint64_t undecodable = 0;              ///< hapticctrl channels whose bytes did not decode
};

/// Writes `<out_dir>/<channel>.csv` (header + one row per message) for every channel named
/// hapticctrl.<instance>.<topic>. Throws std::runtime_error if the log or a file cannot be
/// opened.
CsvReport log_to_csv(const std::string& log_path, const std::string& out_dir);

}  // namespace hapticctrl::lcm_bridge
