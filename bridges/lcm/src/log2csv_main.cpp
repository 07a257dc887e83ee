// hapticctrl-log2csv: an LCM log (lcm-logger) to one CSV per hapticctrl channel.
// usage: hapticctrl-log2csv LOG OUT_DIR
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string_view>

#include "hapticctrl/lcm_bridge/log_csv.hpp"

namespace {

constexpr const char* kUsage =
    "usage: hapticctrl-log2csv LOG OUT_DIR\n"
    "An LCM log recorded with lcm-logger to one CSV per hapticctrl channel in OUT_DIR.\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::string_view(argv[1]) == "--help" || std::string_view(argv[1]) == "-h")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (argc != 3) {
    std::fputs(kUsage, stderr);
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
