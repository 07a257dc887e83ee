// Options declared once with CLI11: numbers range-checked with NaN and infinities refused, usage
// errors naming the option, --help generated from the declarations.
#include "hapticctrl/program/options.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace hapticctrl::program {
namespace {

std::string error_of(Options& o, const std::vector<std::string>& args) {
  try {
    o.parse(args);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

struct Sample {
  int priority = 0;
  double rate = 20.0;
  std::string name = "default";
  bool json = false;
  bool power = true;
  std::vector<std::string> clients;
  std::vector<std::string> positional;
};

void declare(Options& o, Sample& s) {
  o.number("--priority", s.priority, 1, 98, "SCHED_FIFO priority");
  o.number("--rate", s.rate, 1.0, 100.0, "per second");
  o.text("--name", s.name, "a name");
  o.flag("--json", s.json, "JSON");
  o.flag(
      "--no-power", [&s] { s.power = false; }, "no power");
  o.custom(
      "--client", "NET",
      [&s](const std::string& v) {
        if (v.empty() || v[0] == 'x') {
          throw std::invalid_argument("not a network: '" + v + "'");
        }
        s.clients.push_back(v);
      },
      "a client", /*repeat=*/true);
  o.positional("args", s.positional, "the rest");
}

TEST(Options, ParsesEachKindAndKeepsDefaults) {
  Sample s;
  Options o("prog", "A program.");
  declare(o, s);
  ASSERT_TRUE(o.parse({"--priority", "70", "--json", "--no-power", "--client", "a", "--client", "b",
                       "force", "-3", "0.5"}));
  EXPECT_EQ(s.priority, 70);
  EXPECT_DOUBLE_EQ(s.rate, 20.0) << "untouched: the default";
  EXPECT_EQ(s.name, "default");
  EXPECT_TRUE(s.json);
  EXPECT_FALSE(s.power);
  EXPECT_EQ(s.clients, (std::vector<std::string>{"a", "b"})) << "a repeated option, in order";
  EXPECT_EQ(s.positional, (std::vector<std::string>{"force", "-3", "0.5"}))
      << "negative numbers stay positional";
}

TEST(Options, AnErrorNamesItsOptionOnceAndCarriesIt) {
  Sample s;
  Options o("prog", "A program.");
  declare(o, s);
  try {
    o.parse({"--client", "x1"});
    FAIL() << "a bad network was taken";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.option(), "--client") << "the caller decides on the subject, not the text";
    EXPECT_STREQ(e.what(), "--client: not a network: 'x1'");
  }
  Options other("prog", "A program.");
  int port = 0;
  other.custom(
      "--listen", "ADDR",
      [&port](const std::string& v) { port = number_in<int>("--listen port", v, 1, 9); },
      "an address");
  try {
    other.parse({"--listen", "10"});
    FAIL() << "port 10 was taken";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.option(), "--listen port") << "a number's own error, as it was thrown";
    EXPECT_STREQ(e.what(), "--listen port: expected a number from 1 to 9, got '10'");
  }
}

TEST(Options, NumbersOutsideTheirRangeNaNAndInfinityAreRefusedNamingTheOption) {
  for (const std::string bad : {"0", "99", "7.5", "x", "", "nan"}) {
    Sample s;
    Options o("prog", "A program.");
    declare(o, s);
    EXPECT_EQ(error_of(o, {"--priority", bad}),
              "--priority: expected a number from 1 to 98, got '" + bad + "'");
  }
  for (const std::string bad : {"nan", "inf", "-inf", "1e400", "100.5"}) {
    Sample s;
    Options o("prog", "A program.");
    declare(o, s);
    EXPECT_EQ(error_of(o, {"--rate", bad}).rfind("--rate: expected a number from 1 to 100", 0), 0U)
        << bad;
  }
  EXPECT_THROW(number_in<std::uint16_t>("--port", "65536", 0, 65535), std::invalid_argument);
  EXPECT_EQ(number_in<std::uint16_t>("--port", "65535", 0, 65535), 65535);
  EXPECT_DOUBLE_EQ(number_in("--x", "-0.25", -1.0, 1.0), -0.25);
}

TEST(Options, UsageErrorsNameTheOptionAndHelpIsGenerated) {
  Sample s;
  Options o("prog", "A program.");
  declare(o, s);
  EXPECT_EQ(error_of(o, {"--client", "xyz"}), "--client: not a network: 'xyz'");
  Options missing("prog", "A program.");
  declare(missing, s);
  EXPECT_EQ(error_of(missing, {"--name"}), "--name: 1 required TEXT missing");
  Sample t;
  Options no_args("prog", "A program.");
  no_args.number("--priority", t.priority, 1, 98, "SCHED_FIFO priority");
  EXPECT_EQ(error_of(no_args, {"--verbose"}), "The following argument was not expected: --verbose");

  Options help("prog", "A program.");
  declare(help, s);
  EXPECT_FALSE(help.parse({"--json", "--help"})) << "--help asks for the text";
  const std::string text = help.help();
  EXPECT_NE(text.find("A program."), std::string::npos) << text;
  EXPECT_NE(text.find("--priority N"), std::string::npos) << text;
  EXPECT_NE(text.find("SCHED_FIFO priority [1..98]"), std::string::npos) << text;
  EXPECT_NE(text.find("--client NET"), std::string::npos) << text;
}

TEST(Options, AnInstanceIsANameWithoutDotsOrSpaces) {
  std::string instance = "default";
  Options o("prog", "A program.");
  o.instance(instance, "controller instance");
  EXPECT_TRUE(o.parse({"--instance", "lab2"}));
  EXPECT_EQ(instance, "lab2");
  for (const char* bad : {"", "a.b", "a b"}) {
    Options again("prog", "A program.");
    again.instance(instance, "controller instance");
    EXPECT_EQ(error_of(again, {"--instance", bad}),
              "--instance: must be a non-empty name without dots or spaces")
        << bad;
  }
}

}  // namespace
}  // namespace hapticctrl::program
