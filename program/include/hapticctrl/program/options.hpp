#pragma once
/// @file options.hpp
/// A program's command line, declared once with CLI11: the --help text is generated from the
/// declarations, numbers are range-checked with NaN and infinities refused (CLI::Range lets NaN
/// through), and every usage error about an option is an OptionError (a std::invalid_argument)
/// whose text starts with the option's name and whose option() names it; main_skeleton.hpp turns
/// any std::invalid_argument into the project's usage exit (64). A `custom` option's function
/// throws the reason only ("must be sphere or wall"): the option's name is put before it once.
/// CLI11 stays inside options.cpp (GCC's -Wnull-dereference misfires in its string splitting when
/// inlined into a ThreadSanitizer build, 2026-12-02). Setup code: allocates, throws; never called
/// from a cycle.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace hapticctrl::program {

/// A usage error about one option: its text starts with the option's name ("--period-us:
/// expected ..."), and option() names it for a caller that decides on it.
class OptionError : public std::invalid_argument {
 public:
  OptionError(std::string option, const std::string& why)
      : std::invalid_argument(option + ": " + why), option_(std::move(option)) {}
  [[nodiscard]] const std::string& option() const noexcept { return option_; }

 private:
  std::string option_;
};

/// `text` as a T within [lo, hi]: whole for integer types, finite for floating ones. Throws
/// OptionError("<option>: expected a number from LO to HI, got 'TEXT'").
template <typename T>
T number_in(const std::string& option, const std::string& text, T lo, T hi);

/// "LO..HI", as the help text and the errors write a range.
template <typename T>
std::string range_text(T lo, T hi);

class Options {
 public:
  /// `program` names the usage line; `description` heads the --help text.
  Options(const std::string& program, const std::string& description);
  ~Options();
  Options(const Options&) = delete;
  Options& operator=(const Options&) = delete;
  Options(Options&&) = delete;
  Options& operator=(Options&&) = delete;

  /// --name N: a number within [lo, hi] into `target` (its current value is the default shown).
  template <typename T>
  Options& number(const std::string& name, T& target, T lo, T hi, const std::string& help) {
    return custom(
        name, "N",
        [&target, name, lo, hi](const std::string& v) { target = number_in<T>(name, v, lo, hi); },
        help + " [" + range_text(lo, hi) + "]");
  }
  /// --name TEXT into `target`.
  Options& text(const std::string& name, std::string& target, const std::string& help);
  /// --instance NAME into `target`: a controller instance as LCM channel names carry it (not
  /// empty, no dots or spaces).
  Options& instance(std::string& target, const std::string& help);
  /// --name: sets `target`.
  Options& flag(const std::string& name, bool& target, const std::string& help);
  /// --name: calls `on` (a flag that clears a setting, or sets several).
  Options& flag(const std::string& name, std::function<void()> on, const std::string& help);
  /// --name VALUE handed to `apply`, which throws std::invalid_argument for a bad value (its
  /// message is prefixed with the option's name unless it already starts with it). `repeat`: the
  /// option may come more than once (each value applied in order).
  Options& custom(const std::string& name, const std::string& value_name,
                  std::function<void(const std::string&)> apply, const std::string& help,
                  bool repeat = false);

  /// Parses `args` (without the program name). Returns false when --help or -h was given (then
  /// print help()). Throws std::invalid_argument("<option>: <why>") on any usage error.
  bool parse(const std::vector<std::string>& args);
  /// The generated --help text.
  [[nodiscard]] std::string help() const;
  /// The positional arguments, in order, into `target` (negative numbers included).
  Options& positional(const std::string& name, std::vector<std::string>& target,
                      const std::string& help);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The --help text of the options `declare(Options&, Config&)` declares.
template <typename Config, typename Declare>
std::string help_of(const std::string& program, const std::string& description, Declare declare) {
  Config config{};
  Options o(program, description);
  declare(o, config);
  return o.help();
}

/// Parses `args` into `config` through `declare`; false when --help was given.
template <typename Config, typename Declare>
bool parse_into(Config& config, const std::vector<std::string>& args, const std::string& program,
                const std::string& description, Declare declare) {
  Options o(program, description);
  declare(o, config);
  return o.parse(args);
}

}  // namespace hapticctrl::program
