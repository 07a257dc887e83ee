// End to end: hapticctrl-core (simulated arm), hapticctrl-udp, the demo client (two spheres,
// VIRTMECH) and hapticctrl-hmi, all real processes on loopback.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>

#include "hapticctrl/shm/payloads.hpp"
#include "support/controller_stack.hpp"
#include "support/json_fields.hpp"
#include "support/machine_retries.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

/// 4 ms. The demo steps its physics at the controller period: at 10 ms the coupled arm and
/// sphere were still ringing at 1 cm/s after 4 s. And a VM stall of 10 ms (seen on this 2-vCPU
/// VM, 2026-12-01) must cost fewer than the 5 consecutive misses that fail the core safe, as it
/// did at 2 ms.
///
/// Instrumented builds run the behaviour tests' 10 ms cycle: at 4 ms, with ASan+UBSan
/// processes starting beside it, the core still overran and failed safe (2026-12-01). The
/// settling test needs the faster cycle and runs in the plain build only.
#ifdef HAPTICCTRL_SANITIZED
constexpr int kPeriodUs = ControllerStack::kDefaultPeriodUs;
constexpr bool kCrispPhysics = false;
#else
constexpr int kPeriodUs = 4000;
constexpr bool kCrispPhysics = true;
#endif
/// The core derives the coupling stiffness from the object's mass, the client step and the
/// link delay (docs/control.md); for the demo's 0.5 kg sphere it stays above this up to 10 ms.
constexpr double kLeastCouplingStiffness = 200.0;  // N/m
constexpr double kGap = 0.01;                      // the demo's default gap between the spheres

int run_hmi(const ControllerStack& stack, std::vector<std::string> args) {
  args.insert(args.begin(), {"--instance", stack.instance()});
  SpawnedProcess hmi(HAPTICCTRL_HMI_BINARY, args);
  return hmi.wait(20s);
}

double distance(const shm::Pose7& a, const shm::Pose7& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/// The demo client against a fresh controller.
class Demo {
 public:
  Demo(const ControllerStack& stack, std::vector<std::string> extra)
      : process_(HAPTICCTRL_DEMO_BINARY, args_for(stack, std::move(extra))) {}
  [[nodiscard]] bool ready() const {
    return ControllerStack::eventually(
        [&] { return process_.err().find("ready:") != std::string::npos; }, 10s);
  }
  /// SIGTERM, then the JSON summary it prints on the way out.
  std::string finish() {
    process_.signal(SIGTERM);
    status_ = process_.wait(10s);
    return process_.out();
  }
  SpawnedProcess& process() { return process_; }
  [[nodiscard]] int status() const { return status_; }
  [[nodiscard]] std::string err() const { return process_.err(); }

 private:
  static std::vector<std::string> args_for(const ControllerStack& stack,
                                           std::vector<std::string> extra) {
    // Its scene goes to the instance's channel: nothing lands on the default instance's.
    std::vector<std::string> args{"--server",   "127.0.0.1:" + std::to_string(stack.port()),
                                  "--headless", "--json",
                                  "--instance", stack.instance()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  SpawnedProcess process_;
  int status_ = -1;
};

TEST(DemoEndToEnd, BeforePowerOnAnOperatorForceMovesNothingAndNothingIsCoupled) {
  ControllerStack stack("e2e-off", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Demo demo(stack, {"--no-power"});
  ASSERT_TRUE(demo.ready()) << demo.err();
  const shm::Pose7 before = stack.position().handle_pose;
  ASSERT_EQ(run_hmi(stack, {"force", "8", "0", "0", "0", "0", "0"}), 0);
  std::this_thread::sleep_for(700ms);
  const shm::PositionPayload p = stack.position();
  EXPECT_EQ(p.operator_wrench[0], 8.0) << "the core does see the operator's push";
  EXPECT_LT(distance(p.handle_pose, before), 1e-9) << "but the unpowered arm stays on its brakes";
  EXPECT_EQ(stack.vp().object_wrench, shm::Vector6{});
  EXPECT_EQ(stack.vp().state_word & shm::state_bits::kPowered, 0U);
  const std::string json = demo.finish();
  EXPECT_EQ(json_numbers(json, "coupling_wrench"), std::vector<double>(6, 0.0)) << json;
  EXPECT_LT(std::abs(json_numbers(json, "sphere_velocity")[0]), 1e-12) << json;
}

TEST(DemoEndToEnd, PushingTheHandleBringsTheSphereToRestAgainstTheFixedOne) {
  if (!kCrispPhysics) {
    GTEST_SKIP() << "needs the 4 ms cycle; instrumented builds run 10 ms (see kPeriodUs)";
  }
  // Against the demo's wall (a plane 1 cm ahead): pushed into the fixed sphere, the mobile one
  // balances on an unstable equilibrium. The handle rises 2.6 mm as it moves 1.5 cm along x
  // (the arm's kinematics), and a sphere tilted past atan(0.1) = 5.7 deg rolls over the other
  // one (its rolling resistance is 0.1 x N x r). It did so in 2 runs of about 35 here and in both
  // of CI's attempts (sphere at z +4.7 cm, 0.08-0.17 N of contact, 2026-12-03). A stall of
  // 20 ms fails the 4 ms core safe: such an attempt, or one whose check failed while the
  // machine measurably disturbed it, is tried again (machine_retries.hpp).
  retry_what_the_machine_disturbed("push to rest", 3, [](int attempt) {
    ControllerStack stack("e2e-push-" + std::to_string(attempt), kPeriodUs);
    if (!stack.ready()) {
      ADD_FAILURE() << stack.diagnostics();
      return true;
    }
    Demo demo(stack, {"--obstacle", "wall"});
    if (!demo.ready()) {
      ADD_FAILURE() << demo.err();
      return true;
    }
    if (!ControllerStack::eventually(
            [&] { return (stack.vp().state_word & shm::state_bits::kCoupled) != 0; })) {
      ADD_FAILURE() << "the demo powers on and couples";
      return true;
    }
    const double x0 = stack.position().handle_pose[0];
    constexpr double kPush = 5.0;
    EXPECT_EQ(run_hmi(stack, {"force", "5", "0", "0", "0", "0", "0"}), 0);
    std::this_thread::sleep_for(4s);  // reach, touch, settle (about 1.5 s on this machine)
    const shm::PositionPayload p = stack.position();
    const std::string json = demo.finish();
    const auto contact = json_numbers(json, "contact_force");
    const auto sphere = json_numbers(json, "sphere_position");
    const auto velocity = json_numbers(json, "sphere_velocity");
    const auto coupling = json_numbers(json, "coupling_wrench");
    if (contact.size() != 3U || sphere.size() != 3U || velocity.size() != 3U ||
        coupling.size() != 6U) {
      ADD_FAILURE() << "no summary from the demo: " << json << demo.err();
      return true;
    }
    EXPECT_NEAR(-contact[0], kPush, 0.05 * kPush)
        << "at rest the contact holds the operator's push";
    EXPECT_LT(std::hypot(velocity[0], velocity[1], velocity[2]), 0.005) << "the sphere is at rest";
    EXPECT_LT(std::hypot(p.handle_twist[0], p.handle_twist[1], p.handle_twist[2]), 0.005)
        << "the handle is at rest";
    EXPECT_GT(sphere[0] - x0, kGap) << "the sphere travelled the gap (and pressed in)";
    EXPECT_GT(p.handle_pose[0] - x0, kGap) << "the handle came along";
    // The sphere gets the push, and the handle rests where the sphere does: the hand feels the
    // fixed sphere's surface rendered in the servo cycle and the sphere is pressed into it with
    // what the hand feels, each F / K deep (J2; before, the handle led the sphere by the
    // coupling's deflection, push / k).
    EXPECT_NEAR(coupling[0], kPush, 0.05 * kPush);
    EXPECT_NEAR(p.handle_pose[0] - sphere[0], 0.0, 0.1 * kPush / kLeastCouplingStiffness) << json;
    EXPECT_EQ(demo.status(), 0) << demo.err();
    return true;
  });
}

TEST(DemoEndToEnd, AForceOnTheSphereInTheClientMovesTheArmHandle) {
  ControllerStack stack("e2e-client", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string script = "/tmp/hapticctrl-e2e-" + std::to_string(getpid()) + ".script";
  std::ofstream(script) << "0.3 push 0 4 0\n1.3 release\n";
  Demo demo(stack, {"--script", script});
  ASSERT_TRUE(demo.ready()) << demo.err();
  const shm::Pose7 before = stack.position().handle_pose;
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return stack.position().handle_pose[1] - before[1] > 0.01; }, 3s))
      << "handle y moved by " << stack.position().handle_pose[1] - before[1];
  EXPECT_LT(std::abs(stack.position().operator_wrench[1]), 1e-12) << "nobody pushed the handle";
  demo.finish();
  std::remove(script.c_str());
}

TEST(DemoEndToEnd, KillingTheClientFadesTheCouplingAndTheArmStaysPut) {
  ControllerStack stack("e2e-kill", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Demo demo(stack, {});
  ASSERT_TRUE(demo.ready()) << demo.err();
  ASSERT_TRUE(ControllerStack::eventually(
      [&] { return (stack.vp().state_word & shm::state_bits::kCoupled) != 0; }));
  std::this_thread::sleep_for(300ms);
  auto force_norm = [](const shm::VpPayload& vp) {
    return std::hypot(vp.object_wrench[0], vp.object_wrench[1], vp.object_wrench[2]);
  };
  const double before = force_norm(stack.vp());
  demo.process().signal(SIGKILL);
  double largest = 0.0;
  EXPECT_TRUE(ControllerStack::eventually(
      [&] {
        const shm::VpPayload vp = stack.vp();
        largest = std::max(largest, force_norm(vp));
        return (vp.state_word & shm::state_bits::kCoupled) == 0 &&
               vp.object_wrench == shm::Vector6{};
      },
      3s))
      << "the coupling fades to zero once the client falls silent";
  EXPECT_LE(largest, before + 0.05) << "fading, never a spike";
  const shm::Pose7 after_fade = stack.position().handle_pose;
  std::this_thread::sleep_for(1s);
  const shm::PositionPayload p = stack.position();
  EXPECT_LT(distance(p.handle_pose, after_fade), 0.001) << "gravity compensation holds the arm";
  EXPECT_NE(p.state_word & shm::state_bits::kPowered, 0U) << "still powered";
  EXPECT_EQ(stack.vp().core_state, static_cast<std::uint32_t>(shm::CoreState::kRunning));
}

TEST(DemoEndToEnd, StopFromTheHmiShutsTheControllerDownInTheFailSafeOrder) {
  ControllerStack stack("e2e-stop", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Demo demo(stack, {});
  ASSERT_TRUE(demo.ready()) << demo.err();
  ASSERT_TRUE(ControllerStack::eventually(
      [&] { return (stack.vp().state_word & shm::state_bits::kPowered) != 0; }));
  SpawnedProcess hmi(HAPTICCTRL_HMI_BINARY, {"--instance", stack.instance(), "stop"});
  EXPECT_EQ(hmi.wait(20s), 0) << hmi.err();
  EXPECT_NE(hmi.out().find("stopped (stopping, stop requested)"), std::string::npos) << hmi.out();
  EXPECT_EQ(stack.core().wait(10s), 0) << stack.core().err();
  // The closing VP (step 3, "client told") is already unpowered with a zero wrench: steps 1 and
  // 2 came first. The demo saw it and left on its own.
  const shm::VpPayload closing = stack.vp();
  EXPECT_EQ(closing.core_state, static_cast<std::uint32_t>(shm::CoreState::kStopping));
  EXPECT_EQ(closing.state_word & shm::state_bits::kPowered, 0U);
  EXPECT_EQ(closing.object_wrench, shm::Vector6{});
  EXPECT_EQ(demo.process().wait(10s), 0) << demo.err();
  EXPECT_NE(demo.err().find("ended (controller stopped)"), std::string::npos) << demo.err();
  EXPECT_NE(demo.process().out().find("\"powered\":false"), std::string::npos);
  EXPECT_NE(stack.core().err().find("stop requested"), std::string::npos);
}

TEST(DemoEndToEnd, TheDemoRecouplesAfterTenCoreKillsInARow) {
  // J4 review of f3c5aec: after a SIGKILL of the core the demo exited 0 ("controller stopped")
  // while every other process re-attached. A lost controller is not an orderly stop: the demo
  // waits for the next core and couples again through the ramp, kill after kill, once the
  // operator has powered the restarted controller on (J8: a client may not; the demo says it
  // waits for that).
  ControllerStack stack("e2e-kills", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Demo demo(stack, {});
  ASSERT_TRUE(demo.ready()) << demo.err();
  const auto coupled = [&] {
    const std::uint32_t w = stack.vp().state_word;
    return (w & shm::state_bits::kCoupled) != 0 && (w & shm::state_bits::kPowered) != 0;
  };
  ASSERT_TRUE(ControllerStack::eventually(coupled, 5s)) << demo.err();
  for (int kill = 1; kill <= 10; ++kill) {
    stack.core().signal(SIGKILL);
    ASSERT_GE(stack.core().wait(5s), 0);
    stack.start_core();
    ASSERT_TRUE(stack.ready()) << "kill " << kill << ": " << stack.diagnostics();
    const std::string said = "reconnected (" + std::to_string(kill) + ")";
    ASSERT_TRUE(ControllerStack::eventually(
        [&] { return demo.err().find(said) != std::string::npos; }, 15s))
        << "kill " << kill << ": " << demo.err();
    std::this_thread::sleep_for(100ms);  // the demo's power-on request, refused
    EXPECT_EQ(stack.vp().state_word & shm::state_bits::kPowered, 0U)
        << "kill " << kill << ": the demo powered a restarted controller on";
    ASSERT_TRUE(stack.operator_power_on()) << "kill " << kill;
    ASSERT_TRUE(ControllerStack::eventually(coupled, 10s))
        << "kill " << kill << ": not coupled again; " << demo.err();
  }
  EXPECT_EQ(demo.process().wait(0ms), -1) << "the demo runs on: " << demo.err();
  std::size_t lost = 0;
  const std::string err = demo.err();
  for (auto at = err.find("controller lost (killed or crashed)"); at != std::string::npos;
       at = err.find("controller lost (killed or crashed)", at + 1)) {
    ++lost;
  }
  EXPECT_EQ(lost, 10U) << "each loss said as such: " << err;
  EXPECT_NE(err.find("waiting for the operator to power the arm on"), std::string::npos) << err;
  demo.finish();
}

}  // namespace
}  // namespace hapticctrl::test
