// The C API's periodic function against the real controller and bridge.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "hapticctrl/virtuose_api.h"
#include "support/controller_stack.hpp"
#include "virtuose_session.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;
using test::url;
using test::VirtuoseSession;

struct LoopState {
  std::atomic<int> calls{0};
  float push = 3.0F;
};

void periodic(VirtContext vc, void* arg) {
  auto* state = static_cast<LoopState*>(arg);
  ++state->calls;
  float force[6] = {state->push, 0, 0, 0, 0, 0};  // NOLINT(*-avoid-c-arrays)
  float extra[6] = {1, 0, 0, 0, 0, 0};            // NOLINT(*-avoid-c-arrays)
  virtSetForce(vc, force);
  virtAddForce(vc, extra);
}

TEST(VirtuoseLoop, PeriodicFunctionRendersImpedanceForces) {
  ControllerStack stack("capiloop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  VirtContext vc = virtOpen(url(stack).c_str());
  ASSERT_NE(vc, nullptr) << virtGetErrorDetail(nullptr);
  EXPECT_EQ(virtStartLoop(vc), -1);  // no periodic function yet
  LoopState state;
  const float cycle_s = static_cast<float>(stack.period_us()) * 1e-6F;
  float period = 2.2F * cycle_s;  // rounded to two controller cycles, and written back
  ASSERT_EQ(virtSetPeriodicFunction(vc, periodic, &period, &state), 0);
  EXPECT_FLOAT_EQ(period, 2.0F * cycle_s);
  ASSERT_EQ(virtSetCommandType(vc, COMMAND_TYPE_IMPEDANCE), 0);
  ASSERT_EQ(virtSetPowerOn(vc, 1), 0);
  ASSERT_EQ(virtStartLoop(vc), 0);
  EXPECT_TRUE(ControllerStack::eventually([&] {
    return std::abs(stack.vpr().impedance_wrench[0] - 4.0) < 1e-6;  // virtSetForce + virtAddForce
  }));
  state.calls = 0;
  std::this_thread::sleep_for(800ms);
  EXPECT_EQ(virtStopLoop(vc), 0);
  const int expected = 800'000 / (2 * stack.period_us());  // one call every two cycles
  EXPECT_GT(state.calls.load(), expected / 2);
  EXPECT_LT(state.calls.load(), expected * 3 / 2 + 2);
  EXPECT_EQ(virtClose(vc), 0);
}

struct Overrun {
  std::atomic<int> calls{0};
  std::atomic<int> stall_ms{0};  // set by the test, read by the callback
};

TEST(VirtuoseLoop, APeriodicFunctionThatOutlastsItsPeriodRaisesTheOverrunAlarmOnce) {
  ControllerStack stack("capioverrun");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  Overrun state;
  float period = 0.01F;  // long enough that a VM stall inside an empty call is no overrun
  ASSERT_EQ(virtSetPeriodicFunction(
                vc.get(),
                [](VirtContext, void* arg) {
                  auto* s = static_cast<Overrun*>(arg);
                  ++s->calls;
                  std::this_thread::sleep_for(std::chrono::milliseconds(s->stall_ms.load()));
                },
                &period, &state),
            0);
  EXPECT_EQ(virtSetPeriodicFunction(vc.get(), nullptr, &period, &state), -1);
  ASSERT_EQ(virtStartLoop(vc.get()), 0);
  EXPECT_EQ(virtSetPeriodicFunction(
                vc.get(), [](VirtContext, void*) {}, &period, &state),
            -1)
      << "not while the loop runs";
  EXPECT_EQ(virtGetErrorCode(vc.get()), VIRT_E_WRONG_MODE);
  EXPECT_TRUE(ControllerStack::eventually([&] { return state.calls.load() > 10; }));
  unsigned int alarm = 0xFFFFFFFF;
  ASSERT_EQ(virtGetAlarm(vc.get(), &alarm), 0);
  ASSERT_EQ(alarm & VIRT_ALARM_CALLBACK_OVERRUN, 0U) << "an empty function takes microseconds";
  state.stall_ms = 50;  // five periods
  const int before = state.calls.load();
  EXPECT_TRUE(ControllerStack::eventually([&] { return state.calls.load() > before + 1; }));
  state.stall_ms = 0;
  const int stalled = state.calls.load();  // the last stalled call may still be running
  EXPECT_TRUE(ControllerStack::eventually([&] { return state.calls.load() > stalled + 1; }));
  ASSERT_EQ(virtGetAlarm(vc.get(), &alarm), 0);
  EXPECT_NE(alarm & VIRT_ALARM_CALLBACK_OVERRUN, 0U);
  std::this_thread::sleep_for(100ms);
  ASSERT_EQ(virtGetAlarm(vc.get(), &alarm), 0);
  EXPECT_EQ(alarm & VIRT_ALARM_CALLBACK_OVERRUN, 0U) << "reading the alarm cleared it";
  ASSERT_EQ(virtStopLoop(vc.get()), 0);
}

struct StopsItself {
  std::atomic<int> calls{0};
  std::atomic<int> stop_result{1};
};

TEST(VirtuoseLoop, APeriodicFunctionMayStopTheLoopItRunsIn) {
  // virtStopLoop from inside the periodic function waited for the function itself to return
  // (the callback's own mutex; noticed 2026-12-06): now the loop ends when the function returns.
  ControllerStack stack("capiselfstop");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const VirtuoseSession vc(stack);
  ASSERT_TRUE(vc.open()) << virtGetErrorDetail(nullptr);
  StopsItself state;
  float period = static_cast<float>(stack.period_us()) * 1e-6F;
  ASSERT_EQ(virtSetPeriodicFunction(
                vc.get(),
                [](VirtContext v, void* arg) {
                  auto* s = static_cast<StopsItself*>(arg);
                  if (++s->calls == 5) {
                    s->stop_result = virtStopLoop(v);
                  }
                },
                &period, &state),
            0);
  ASSERT_EQ(virtStartLoop(vc.get()), 0);
  ASSERT_TRUE(ControllerStack::eventually([&] { return state.stop_result.load() == 0; }))
      << state.calls.load() << " calls, virtStopLoop not returned";
  std::this_thread::sleep_for(300ms);  // 30 cycles: none calls the function any more
  EXPECT_EQ(state.calls.load(), 5);
  ASSERT_EQ(virtStartLoop(vc.get()), 0) << "and it starts again";
  EXPECT_TRUE(ControllerStack::eventually([&] { return state.calls.load() > 6; }));
  EXPECT_EQ(virtStopLoop(vc.get()), 0);
}

}  // namespace
}  // namespace hapticctrl
