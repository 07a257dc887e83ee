// Tests of bench/netem/src/main.cpp's command line: declared through program/ like every other
// program (generated --help, usage errors naming the option, exit 64), and the relay's start-up
// checks (a remote address refused without --allow-remote).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/spawned_process.hpp"

namespace {

using hapticctrl::test::SpawnedProcess;
using testing::HasSubstr;

struct Outcome {
  int status;
  std::string out;
  std::string err;
};

Outcome netem(const std::vector<std::string>& args) {
  SpawnedProcess p(HAPTICCTRL_NETEM_BINARY, args);
  const int status = p.wait();
  return {status, p.out(), p.err()};
}

TEST(NetemMain, HelpListsEveryOptionAndExitsZero) {
  const Outcome r = netem({"--help"});
  EXPECT_EQ(r.status, 0);
  for (const char* option :
       {"--listen", "--to", "--delay-ms", "--jitter-ms", "--loss", "--burst", "--reorder",
        "--blackout", "--seed", "--duration", "--allow-remote", "--json"}) {
    EXPECT_THAT(r.out, HasSubstr(option));
  }
}

TEST(NetemMain, UsageErrorsNameTheOptionAndExit64) {
  const Outcome no_target = netem({"--delay-ms", "5"});
  EXPECT_EQ(no_target.status, 64);
  EXPECT_THAT(no_target.err, HasSubstr("--to"));

  const Outcome nan_delay = netem({"--to", "127.0.0.1:5125", "--delay-ms", "nan"});
  EXPECT_EQ(nan_delay.status, 64);
  EXPECT_THAT(nan_delay.err, HasSubstr("--delay-ms"));

  const Outcome loss = netem({"--to", "127.0.0.1:5125", "--loss", "1.5"});
  EXPECT_EQ(loss.status, 64);
  EXPECT_THAT(loss.err, HasSubstr("--loss"));

  const Outcome blackout = netem({"--to", "127.0.0.1:5125", "--blackout", "2"});
  EXPECT_EQ(blackout.status, 64);
  EXPECT_THAT(blackout.err, HasSubstr("AT:DURATION"));

  const Outcome unknown = netem({"--to", "127.0.0.1:5125", "--lose", "0.1"});
  EXPECT_EQ(unknown.status, 64);
  EXPECT_THAT(unknown.err, HasSubstr("--lose"));
}

TEST(NetemMain, RefusesARemoteAddressUnlessAllowed) {
  const Outcome r = netem({"--to", "192.0.2.1:5125", "--duration", "0.1"});
  EXPECT_EQ(r.status, 64);
  EXPECT_THAT(r.err, HasSubstr("not on loopback"));
}

TEST(NetemMain, RelaysForItsDurationAndPrintsItsCounters) {
  const Outcome r = netem({"--to", "127.0.0.1:9", "--delay-ms", "2", "--blackout", "0:0.05",
                           "--duration", "0.2", "--json"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("listening on 127.0.0.1:"));
  EXPECT_THAT(r.out, HasSubstr("{"));
}

}  // namespace
