#include "hapticctrl/hmi/hmi_options.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::hmi {
namespace {

TEST(HmiOptions, NoCommandOpensThePanelOnTheDefaultInstance) {
  const HmiOptions o = HmiOptions::parse({});
  EXPECT_EQ(o.command, HmiCommand::kPanel);
  EXPECT_EQ(o.instance, "default");
}

TEST(HmiOptions, ParsesOneShotCommandsWithTheirArguments) {
  EXPECT_EQ(HmiOptions::parse({"--instance", "lab", "power-on"}).command, HmiCommand::kPowerOn);
  EXPECT_EQ(HmiOptions::parse({"estop"}).command, HmiCommand::kEmergencyStop);
  const HmiOptions status = HmiOptions::parse({"status", "--json"});
  EXPECT_EQ(status.command, HmiCommand::kStatus);
  EXPECT_TRUE(status.json);
  const HmiOptions force = HmiOptions::parse({"force", "-5", "0", "2.5", "0", "0", "-0.1"});
  EXPECT_EQ(force.command, HmiCommand::kForce);
  EXPECT_EQ(force.wrench, (shm::Vector6{-5, 0, 2.5, 0, 0, -0.1}));
  const HmiOptions play = HmiOptions::parse({"play", "seq.txt", "--power-on", "--log", "-"});
  EXPECT_EQ(play.sequence_path, "seq.txt");
  EXPECT_EQ(play.log_path, "-");
  EXPECT_TRUE(play.power_on);
  EXPECT_EQ(HmiOptions::parse({"play", "s.txt"}).log_path, "hapticctrl-sequence.csv");
  EXPECT_EQ(HmiOptions::parse({"--timeout-ms", "250", "reset"}).timeout.count(), 250);
}

TEST(HmiOptions, RefusesWhatItCannotDoWithAClearMessage) {
  auto message = [](const std::vector<std::string>& args) {
    try {
      (void)HmiOptions::parse(args);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message({"launch"}), "unknown command 'launch'");
  EXPECT_EQ(message({"force", "1", "2"}), "force needs 6 numbers: FX FY FZ TX TY TZ");
  EXPECT_NE(message({"force", "1", "2", "x", "0", "0", "0"}).find("force component 3"),
            std::string::npos);
  EXPECT_NE(message({"force", "nan", "0", "0", "0", "0", "0"}).find("finite"), std::string::npos);
  EXPECT_EQ(message({"play"}), "play needs one sequence file");
  EXPECT_EQ(message({"power-on", "now"}), "unexpected argument 'now'");
  EXPECT_EQ(message({"power-on", "--json"}), "--json goes with the status command");
  EXPECT_EQ(message({"--instance"}), "--instance needs a value");
  EXPECT_EQ(message({"--verbose"}), "unknown option '--verbose'");
  EXPECT_NE(message({"--timeout-ms", "0", "stop"}).find("1..600000"), std::string::npos);
}

}  // namespace
}  // namespace hapticctrl::hmi
