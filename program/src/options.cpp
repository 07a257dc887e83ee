// Options declared once with CLI11 (options.hpp).
#include "hapticctrl/program/options.hpp"

// GCC 12 reports a null dereference inside CLI11's string splitting once it is inlined into a
// ThreadSanitizer build (-O2 -fsanitize=thread); the code is correct (2026-12-02).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop

#include <charconv>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace hapticctrl::program {
namespace {

template <typename T>
std::string text_of(T value) {
  std::ostringstream out;
  out << +value;  // + prints 8-bit integers as numbers
  return out.str();
}

}  // namespace

template <typename T>
T number_in(const std::string& option, const std::string& text, T lo, T hi) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  // Written so that NaN is out of range too.
  if (ec != std::errc() || ptr != end || !(value >= lo && value <= hi)) {
    throw OptionError(option, "expected a number from " + text_of(lo) + " to " + text_of(hi) +
                                  ", got '" + text + "'");
  }
  return value;
}

template <typename T>
std::string range_text(T lo, T hi) {
  return text_of(lo) + ".." + text_of(hi);
}

template int number_in<int>(const std::string&, const std::string&, int, int);
template std::uint16_t number_in<std::uint16_t>(const std::string&, const std::string&,
                                                std::uint16_t, std::uint16_t);
template std::uint32_t number_in<std::uint32_t>(const std::string&, const std::string&,
                                                std::uint32_t, std::uint32_t);
template std::uint64_t number_in<std::uint64_t>(const std::string&, const std::string&,
                                                std::uint64_t, std::uint64_t);
template std::int64_t number_in<std::int64_t>(const std::string&, const std::string&, std::int64_t,
                                              std::int64_t);
template double number_in<double>(const std::string&, const std::string&, double, double);
template std::string range_text<int>(int, int);
template std::string range_text<std::uint16_t>(std::uint16_t, std::uint16_t);
template std::string range_text<std::uint32_t>(std::uint32_t, std::uint32_t);
template std::string range_text<std::uint64_t>(std::uint64_t, std::uint64_t);
template std::string range_text<std::int64_t>(std::int64_t, std::int64_t);
template std::string range_text<double>(double, double);

struct Options::Impl {
  Impl(const std::string& program, const std::string& description) : app(description, program) {}
  CLI::App app;
};

Options::Options(const std::string& program, const std::string& description)
    : impl_(std::make_unique<Impl>(program, description)) {
  impl_->app.set_help_flag("-h,--help", "this text");
  impl_->app.get_formatter()->column_width(28);
}

Options::~Options() = default;

Options& Options::positional(const std::string& name, std::vector<std::string>& target,
                             const std::string& help) {
  impl_->app.add_option(name, target, help);
  return *this;
}

Options& Options::text(const std::string& name, std::string& target, const std::string& help) {
  return custom(
      name, "TEXT", [&target](const std::string& v) { target = v; }, help);
}

Options& Options::instance(std::string& target, const std::string& help) {
  return custom(
      "--instance", "NAME",
      [&target](const std::string& v) {
        if (v.empty() || v.find_first_of(". \t") != std::string::npos) {
          throw std::invalid_argument("must be a non-empty name without dots or spaces");
        }
        target = v;
      },
      help);
}

Options& Options::flag(const std::string& name, bool& target, const std::string& help) {
  return flag(
      name, [&target] { target = true; }, help);
}

Options& Options::flag(const std::string& name, std::function<void()> on, const std::string& help) {
  impl_->app.add_flag_callback(name, std::move(on), help);
  return *this;
}

Options& Options::custom(const std::string& name, const std::string& value_name,
                         std::function<void(const std::string&)> apply, const std::string& help,
                         bool repeat) {
  const auto checked = [name, apply = std::move(apply)](const std::string& value) {
    try {
      apply(value);
    } catch (const OptionError&) {
      throw;  // it names its option already
    } catch (const std::invalid_argument& e) {
      throw OptionError(name, e.what());
    }
  };
  if (repeat) {
    impl_->app
        .add_option_function<std::vector<std::string>>(
            name,
            [checked](const std::vector<std::string>& values) {
              for (const std::string& v : values) {
                checked(v);
              }
            },
            help)
        ->type_name(value_name)
        ->allow_extra_args(false)  // one value per occurrence, never the arguments after it
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  } else {
    impl_->app.add_option_function<std::string>(name, checked, help)
        ->type_name(value_name)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
  return *this;
}

bool Options::parse(const std::vector<std::string>& args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 pops from the back
  try {
    impl_->app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    return false;
  } catch (const CLI::ParseError& e) {
    throw std::invalid_argument(e.what());
  }
  return true;
}

std::string Options::help() const {
  return impl_->app.help();
}

}  // namespace hapticctrl::program
