// hapticctrl-log2csv: an LCM log (lcm-logger) to one CSV per hapticctrl channel.
// usage: hapticctrl-log2csv LOG OUT_DIR
#include <cstdio>
#include <exception>
#include <filesystem>

#include "hapticctrl/lcm_bridge/log_csv.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: hapticctrl-log2csv LOG OUT_DIR\n");
    return 64;
  }
  try {
    std::filesystem::create_directories(argv[2]);
    const auto report = hapticctrl::lcm_bridge::log_to_csv(argv[1], argv[2]);
    for (const auto& [file, rows] : report.rows) {
      std::printf("%s/%s: %llu rows\n", argv[2], file.c_str(),
                  static_cast<unsigned long long>(rows));
    }
    if (report.undecodable != 0 || report.skipped != 0) {
      std::printf("skipped %llu events of other channels, %llu that did not decode\n",
                  static_cast<unsigned long long>(report.skipped),
                  static_cast<unsigned long long>(report.undecodable));
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapticctrl-log2csv: %s\n", e.what());
    return 1;
  }
}
