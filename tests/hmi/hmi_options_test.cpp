// Tests of hmi_options.hpp: command line of hapticctrl-hmi.
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
  const HmiOptions hand =
      HmiOptions::parse({"play", "s.txt", "--hand", "400,8", "--wander", "0.02", "--seed", "9"});
  EXPECT_TRUE(hand.with_hand);
  EXPECT_EQ(hand.hand.stiffness, 400.0);
  EXPECT_EQ(hand.hand.damping, 8.0);
  EXPECT_EQ(hand.hand.wander, 0.02);
  EXPECT_EQ(hand.hand.seed, 9U);
  EXPECT_EQ(hand.hand.angular_stiffness, 0.0) << "no wrist unless asked";
  const HmiOptions wrist = HmiOptions::parse({"play", "s.txt", "--hand", "100,5,2,0.05"});
  EXPECT_EQ(wrist.hand.stiffness, 100.0);
  EXPECT_EQ(wrist.hand.angular_stiffness, 2.0);
  EXPECT_EQ(wrist.hand.angular_damping, 0.05);
  EXPECT_FALSE(play.with_hand);
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
  const std::string needs =
      "--hand: needs K,B (stiffness N/m, damping N.s/m) or K,B,KA,BA (and the wrist's N.m/rad, "
      "N.m.s/rad)";
  EXPECT_EQ(message({"play", "s", "--hand", "400"}), needs);
  EXPECT_EQ(message({"play", "s", "--hand", "400,5,2"}), needs);
  EXPECT_NE(message({"play", "s", "--hand", "400,5,40,0.1"}).find("0..30 N.m/rad"),
            std::string::npos);
  EXPECT_NE(message({"play", "s", "--hand", "9000,5"}).find("0..3000 N/m"), std::string::npos);
  EXPECT_NE(message({"play", "s", "--hand", "400,5", "--wander", "1"}).find("0..0.1 m"),
            std::string::npos);
  EXPECT_EQ(message({"play", "s", "--wander", "0.01"}), "--wander and --seed need --hand K,B");
  EXPECT_EQ(message({"status", "--hand", "1,1"}),
            "--hand, --wander and --seed go with the play command");
  EXPECT_NE(message({"play", "s", "--hand", "4,1", "--seed", "1.5"})
                .find("--seed: expected a number from 0 to 1000000000000000, got '1.5'"),
            std::string::npos);
  EXPECT_EQ(message({"power-on", "--json"}), "--json goes with the status command");
  EXPECT_EQ(message({"--instance"}), "--instance: 1 required TEXT missing");
  EXPECT_EQ(message({"--verbose"}), "The following argument was not expected: --verbose");
  EXPECT_NE(message({"--timeout-ms", "0", "stop"}).find("from 1 to 600000"), std::string::npos);
}

}  // namespace
}  // namespace hapticctrl::hmi
