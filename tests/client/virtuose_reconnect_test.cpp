// The C API's way back to the controller (J4): a VirtuoseAPI application whose controller is
// killed keeps its context; the library opens a session with the next controller, replays what
// the application set and moves its periodic function there. Real core and bridge on loopback.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <vector>

#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/virtuose_api.h"
#include "support/controller_stack.hpp"
#include "virtuose_session.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;
using test::VirtuoseSession;

/// The application: a VIRTMECH object held 1 cm beside where the handle was at the start (so
/// that every new controller's coupling has a stretched spring to ramp in), set in the loop.
struct Application {
  std::atomic<int> calls{0};
  float held[7] = {0, 0, 0, 0, 0, 0, 1};  // NOLINT(*-avoid-c-arrays): the C API's pose
};

void periodic(VirtContext vc, void* arg) {
  auto* app = static_cast<Application*>(arg);
  ++app->calls;
  virtSetPosition(vc, app->held);
}

/// What the application set, as the controller has it from the bridge.
void expect_settings_in_force(const shm::VprPayload& v, double step_s) {
  EXPECT_EQ(v.command_type, static_cast<std::uint32_t>(shm::CommandType::kVirtmech));
  EXPECT_NEAR(v.object_mass, 0.2, 1e-6);
  EXPECT_NEAR(v.object_inertia[1], 2e-4, 1e-9);
  EXPECT_NEAR(v.force_factor, 0.5, 1e-6);
  EXPECT_NEAR(v.client_time_step, step_s, 1e-9);
  EXPECT_NEAR(v.force_limits[0], 6.0, 1e-6);
  EXPECT_EQ(v.watchdog_timeout_us, 400'000U);
  EXPECT_EQ(v.contact_count, 1U);
}

TEST(VirtuoseReconnect, AContextComesBackAfterTenCoreKillsWithWhatTheApplicationSet) {
  ControllerStack stack("capirecon");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  const float step = static_cast<float>(stack.period_us()) * 1e-6F;
  Application app;
  ASSERT_EQ(virtGetPhysicalPosition(vc.get(), app.held), 0);
  app.held[0] += 0.01F;
  float inertia[3] = {2e-4F, 2e-4F, 2e-4F};                        // NOLINT(*-avoid-c-arrays)
  float wall[11] = {0, 0, -0.05F, 0, 0, 1, 0.01F, 1000, 0, 0, 0};  // NOLINT(*-avoid-c-arrays)
  float period = step;
  ASSERT_EQ(virtSetTimeStep(vc.get(), step), 0) << vc.detail();
  ASSERT_EQ(virtSetForceFactor(vc.get(), 0.5F), 0) << vc.detail();
  ASSERT_EQ(virtSetCommandType(vc.get(), COMMAND_TYPE_VIRTMECH), 0) << vc.detail();
  ASSERT_EQ(virtAttachVO(vc.get(), 0.2F, inertia), 0) << vc.detail();
  ASSERT_EQ(virtSaturateTorque(vc.get(), 6.0F, 0.5F), 0) << vc.detail();
  ASSERT_EQ(virtSetTimeoutValue(vc.get(), 0.4F), 0) << vc.detail();
  ASSERT_EQ(virtSetContacts(vc.get(), 1, wall), 0) << vc.detail();
  ASSERT_EQ(virtSetPeriodicFunction(vc.get(), periodic, &period, &app), 0) << vc.detail();
  ASSERT_EQ(virtStartLoop(vc.get()), 0) << vc.detail();
  ASSERT_EQ(virtSetPowerOn(vc.get(), 1), 0) << vc.detail();
  ASSERT_TRUE(ControllerStack::eventually(
      [&] { return (stack.vp().state_word & shm::state_bits::kCoupled) != 0; }));
  expect_settings_in_force(stack.vpr(), static_cast<double>(step));

  std::vector<double> coupled_after_ms;
  for (int kill = 1; kill <= 10; ++kill) {
    SCOPED_TRACE("kill " + std::to_string(kill));
    stack.core().signal(SIGKILL);
    stack.core().wait(5s);
    float pose[7] = {};  // NOLINT(*-avoid-c-arrays)
    ASSERT_TRUE(ControllerStack::eventually([&] { return virtGetPosition(vc.get(), pose) != 0; }))
        << "the getters went on as if the arm were there";
    EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_COMMUNICATION_FAILURE) << vc.detail();
    EXPECT_NE(vc.detail().find("controller lost"), std::string::npos) << vc.detail();
    EXPECT_EQ(virtSetForceFactor(vc.get(), 0.7F), -1);  // refused meanwhile, and not replayed
    EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_COMMUNICATION_FAILURE) << vc.detail();

    stack.start_core();
    ASSERT_TRUE(stack.ready()) << stack.diagnostics();
    const auto started = std::chrono::steady_clock::now();
    // The restarted core waits for its operator before any client may power the arm (J8).
    ASSERT_TRUE(ControllerStack::eventually([&] {
      return stack.vpr().session_id != 0 && stack.vpr().contact_count == 1;
    })) << "no session with the next controller";
    ASSERT_TRUE(stack.operator_power_on()) << stack.diagnostics();
    ASSERT_TRUE(ControllerStack::eventually([&] {
      return (stack.vp().state_word & shm::state_bits::kCoupled) != 0;
    })) << "not coupled again";
    coupled_after_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
            .count());
    expect_settings_in_force(stack.vpr(), static_cast<double>(step));
    EXPECT_EQ(virtGetPosition(vc.get(), pose), 0) << vc.detail();
    const int calls = app.calls.load();
    EXPECT_TRUE(ControllerStack::eventually([&] { return app.calls.load() > calls + 10; }))
        << "the periodic function does not run on the new session";
  }
  std::printf("core started to coupled again (operator's power-on included):");
  for (const double ms : coupled_after_ms) {
    std::printf(" %.0f", ms);
  }
  std::printf(" ms\n");
  EXPECT_EQ(virtStopLoop(vc.get()), 0);
}

TEST(VirtuoseReconnect, AnOrderlyStopEndsTheSessionAndVirtCloseIsPromptMeanwhile) {
  ControllerStack stack("capistop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  VirtContext vc = virtOpen(test::url(stack).c_str());
  ASSERT_NE(vc, nullptr) << virtGetErrorDetail(nullptr);
  stack.core().signal(SIGTERM);  // an operator's stop
  stack.core().wait(5s);
  float pose[7] = {};  // NOLINT(*-avoid-c-arrays)
  ASSERT_TRUE(ControllerStack::eventually([&] { return virtGetPosition(vc, pose) != 0; }));
  EXPECT_NE(std::string(virtGetErrorDetail(vc)).find("in order"), std::string::npos)
      << virtGetErrorDetail(vc);
  stack.start_core();
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  std::this_thread::sleep_for(1s);
  EXPECT_EQ(stack.vpr().session_id, 0U) << "the library reconnected after an orderly stop";
  EXPECT_NE(virtGetPosition(vc, pose), 0);
  EXPECT_EQ(virtClose(vc), 0);

  // Killed with no controller to follow: the library keeps trying until virtClose, which
  // returns within one attempt.
  VirtContext again = virtOpen(test::url(stack).c_str());
  ASSERT_NE(again, nullptr) << virtGetErrorDetail(nullptr);
  stack.core().signal(SIGKILL);
  stack.core().wait(5s);
  ASSERT_TRUE(ControllerStack::eventually([&] { return virtGetPosition(again, pose) != 0; }));
  std::this_thread::sleep_for(700ms);  // into an attempt
  const auto closing = std::chrono::steady_clock::now();
  virtClose(again);
  EXPECT_LT(std::chrono::steady_clock::now() - closing, 1500ms);
}

}  // namespace
}  // namespace hapticctrl
