#pragma once
/// @file main_skeleton.hpp
/// The main() every hapticctrl program shares, so that they report and exit alike: the options
/// are parsed (a usage error prints "<program>: <why>" and "see --help" on stderr and exits 64),
/// --help prints the generated text (exit 0), then `run` runs: its return value is the exit
/// status; a std::invalid_argument it throws (a value found bad while starting) exits 64, any
/// other exception prints "<program>: error: <what>" and exits 1. Setup code.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace hapticctrl::program {

/// The usage exit status (sysexits' EX_USAGE).
inline constexpr int kUsageExit = 64;

/// `parse(args, config)` returns false for --help; `help()` gives the text to print then.
template <typename Config, typename Parse, typename Help, typename Run>
int main_skeleton(const char* program, int argc, char** argv, Parse parse, Help help, Run run) {
  Config config{};
  try {
    if (!parse(std::vector<std::string>(argv + 1, argv + argc), config)) {
      const std::string text = help();
      std::printf("%s", text.c_str());
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n(see %s --help)\n", program, e.what(), program);
    return kUsageExit;
  }
  try {
    return run(config);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return kUsageExit;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace hapticctrl::program
