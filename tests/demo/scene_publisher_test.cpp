// Tests of scene_publisher.hpp: publishes the demo's scene (scene_t) on LCM so that operator views
// (the web bridge, lcm-spy) can draw the spheres the controller's handle is coupled to.
#include "hapticctrl/demo/scene_publisher.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "hapticctrl/lcmtypes/channels.hpp"

namespace hapticctrl::demo {
namespace {

using namespace std::chrono_literals;

SphereScene touching_scene() {
  SceneConfig config;
  config.fixed_center = {0.1, 0.0, 0.2};
  SphereState start;
  start.position = {0.1 + 0.059, 0.0, 0.2};  // 1 mm into the fixed sphere
  return {config, start};
}

TEST(SceneMessage, CarriesTheSpheresTheContactAndTheLink) {
  const SphereScene scene = touching_scene();
  AppliedWrench applied;
  applied.wrench[1] = 2.0;
  client::LinkStatistics link;
  link.rtt_last_us = 900.0;
  link.rtt_mean_us = 850.0;
  link.rtt_max_us = 2000.0;
  link.answers_received = 1000;
  link.answers_lost = 3;
  const auto m = to_scene_message(scene, applied, link, 77, 123);
  EXPECT_EQ(m.utime, 123);
  EXPECT_EQ(m.steps, 77);
  EXPECT_EQ(m.fixed_center[2], 0.2);
  EXPECT_EQ(m.fixed_radius, 0.03);
  EXPECT_EQ(m.mobile_pose[0], 0.159);
  EXPECT_EQ(m.mobile_pose[6], 1.0);
  EXPECT_NEAR(m.penetration, 0.001, 1e-12);
  EXPECT_GT(m.contact_force[0], 0.0);  // pushes the mobile sphere away along +x
  EXPECT_EQ(m.applied_wrench[1], 2.0);
  EXPECT_EQ(m.rtt_last_us, 900.0);
  EXPECT_EQ(m.rtt_max_us, 2000.0);
  EXPECT_EQ(m.answers_received, 1000);
  EXPECT_EQ(m.answers_lost, 3);
}

TEST(ScenePublisher, IsDueOncePerPeriodAndNeverBursts) {
  ScenePublisher p("memq://", "t", 10.0);  // every 100 ms
  EXPECT_TRUE(p.due(TimePoint{1000ms}));
  EXPECT_FALSE(p.due(TimePoint{1050ms}));
  EXPECT_TRUE(p.due(TimePoint{1100ms}));
  EXPECT_TRUE(p.due(TimePoint{2000ms}));   // after a stall: one now...
  EXPECT_FALSE(p.due(TimePoint{2050ms}));  // ...and the next a period later, not a catch-up burst
  EXPECT_TRUE(p.due(TimePoint{2100ms}));
}

TEST(ScenePublisher, PublishesOnTheInstancesSceneChannel) {
  const std::string instance = "scenetest" + std::to_string(getpid());
  lcm::LCM listener(lcmtypes::kDefaultLcmUrl);
  ASSERT_TRUE(listener.good());
  hapticctrl_lcm::scene_t got{};
  bool received = false;
  struct Sink {
    hapticctrl_lcm::scene_t* out;
    bool* flag;
  } sink{&got, &received};
  listener.subscribeFunction(
      lcmtypes::Channels::of(instance).scene,
      +[](const lcm::ReceiveBuffer* rbuf, const std::string& /*ch*/, Sink* s) {
        *s->flag = s->out->decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0;
      },
      &sink);
  ScenePublisher p(lcmtypes::kDefaultLcmUrl, instance, 30.0);
  EXPECT_EQ(p.channel(), "hapticctrl." + instance + ".scene");
  hapticctrl_lcm::scene_t sent{};
  sent.steps = 5;
  ASSERT_TRUE(p.publish(sent));
  for (int i = 0; i < 100 && !received; ++i) {
    listener.handleTimeout(20);
  }
  ASSERT_TRUE(received);
  EXPECT_EQ(got.steps, 5);
}

TEST(ScenePublisher, SaysWhichUrlItCannotOpen) {
  try {
    ScenePublisher p("nonsense://x", "t", 30.0);
    FAIL() << "opened a nonsense URL";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("nonsense://x"));
    EXPECT_THAT(e.what(), testing::HasSubstr("--no-lcm"));
  }
}

}  // namespace
}  // namespace hapticctrl::demo
