// Tests of run_summary.hpp: the engine's load per step and the end-of-run JSON.
#include "hapticctrl/mujoco/run_summary.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hapticctrl::mujoco {
namespace {

using testing::HasSubstr;

TEST(RunSummary, TheLoadKeepsTheMeanAndTheWorstStep) {
  EngineLoad load;
  EXPECT_EQ(load.mean_us(), 0.0) << "no step yet";
  load.add(10'000);
  load.add(30'000);
  EXPECT_DOUBLE_EQ(load.mean_us(), 20.0);
  EXPECT_EQ(load.cpu_max_ns, 30'000);
}

TEST(RunSummary, TheJsonSaysTheBodyTheEngineAndWhatTheHandMoved) {
  RunSummary s;
  s.ended = "duration";
  s.body = "block";
  s.mass = 0.5;
  s.timestep = 0.002;
  s.body_pose = {0.1, 0.2, 0.3, 0, 0, 0, 1};
  s.steps = 1000;
  s.steps_per_second = 499.6;
  s.load.add(40'000);
  s.contacts_supported = false;
  s.bodies = {{"lid", {1, 2, 3}}, {"peg", {0, 0, 0.05}}};
  s.joints = {{"hinge", 0.25}};
  const std::string json = summary_json(s);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
  EXPECT_THAT(json, HasSubstr("\"ended\":\"duration\",\"body\":\"block\",\"mass\":0.5,"));
  EXPECT_THAT(json, HasSubstr("\"body_pose\":[0.100000,0.200000,0.300000,"));
  EXPECT_THAT(json, HasSubstr("\"steps_per_second\":499.6,\"model_steps_per_second\":500.0,"));
  EXPECT_THAT(json, HasSubstr("\"cpu_us_per_step_mean\":40.00,\"cpu_us_per_step_max\":40.0,"));
  EXPECT_THAT(json, HasSubstr("\"contacts_supported\":false,"));
  EXPECT_THAT(json, HasSubstr("\"bodies\":{\"lid\":[1.000000,2.000000,3.000000],\"peg\":"));
  EXPECT_THAT(json, HasSubstr("\"joints\":{\"hinge\":0.250000}}"));
}

}  // namespace
}  // namespace hapticctrl::mujoco
