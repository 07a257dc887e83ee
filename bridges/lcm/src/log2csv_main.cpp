// hapticctrl-log2csv: an LCM log (lcm-logger) to one CSV per hapticctrl channel.
// usage: hapticctrl-log2csv --log FILE --out DIR
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "hapticctrl/lcm_bridge/log_csv.hpp"
#include "hapticctrl/program/main_skeleton.hpp"
#include "hapticctrl/program/options.hpp"

namespace {

constexpr const char* kProgram = "hapticctrl-log2csv";
constexpr const char* kDescription =
    "An LCM log recorded with lcm-logger to one CSV per hapticctrl channel.";

struct Log2CsvOptions {
  std::string log;
  std::string out;
};

void declare(hapticctrl::program::Options& o, Log2CsvOptions& c) {
  o.text("--log", c.log, "the LCM log to read (required)");
  o.text("--out", c.out, "the folder to write the CSV files to, made if missing (required)");
}

bool parse(const std::vector<std::string>& args, Log2CsvOptions& c) {
  if (!hapticctrl::program::parse_into(c, args, kProgram, kDescription, declare)) {
    return false;
  }
  if (c.log.empty() || c.out.empty()) {
    throw std::invalid_argument("--log FILE and --out DIR are required");
  }
  return true;
}

int convert(const Log2CsvOptions& c) {
  std::filesystem::create_directories(c.out);
  const auto report = hapticctrl::lcm_bridge::log_to_csv(c.log, c.out);
  for (const auto& [file, rows] : report.rows) {
    std::printf("%s/%s: %llu rows\n", c.out.c_str(), file.c_str(),
                static_cast<unsigned long long>(rows));
  }
  if (report.undecodable != 0 || report.skipped != 0) {
    std::printf("skipped %llu events of other channels, %llu that did not decode\n",
                static_cast<unsigned long long>(report.skipped),
                static_cast<unsigned long long>(report.undecodable));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::program::main_skeleton<Log2CsvOptions>(
      kProgram, argc, argv, parse,
      [] { return hapticctrl::program::help_of<Log2CsvOptions>(kProgram, kDescription, declare); },
      convert);
}
