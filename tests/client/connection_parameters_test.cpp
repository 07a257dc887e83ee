// The parameter calls (connection_parameters.cpp) against the real hapticctrl-core and
// hapticctrl-udp on loopback.
#include "hapticctrl/client/connection.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "support/controller_stack.hpp"
#include "support/reference_parameters.hpp"

namespace hapticctrl::client {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

Address address_of(const ControllerStack& stack) {
  return {"127.0.0.1", stack.port()};
}

TEST(ConnectionParameters, EveryParameterReachesTheController) {
  ControllerStack stack("params");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  c.set_time_step(0.002);
  c.set_force_factor(0.5);
  c.set_speed_factor(2.0);
  c.set_base_frame({0, 0, 0.1, 0, 0, 0, 1});
  c.set_observation_frame({-0.1, 0, 0, 0, 0, 0, 1});
  c.set_indexing_mode(IndexingMode::kTranslation);
  c.set_command_type(CommandType::kVirtmech);
  c.attach_object(0.3, {0.001, 0.002, 0.003});
  c.set_gains(800, 5, 2, 0.05);
  c.set_force_limits(10, 1);
  c.set_watchdog(300ms);
  test::expect_reference_parameters(stack.vpr());
  c.detach_object();
  EXPECT_EQ(stack.vpr().flags & shm::vpr_flags::kObjectAttached, 0U);
  EXPECT_EQ(c.watchdog_ms(), 300U);

  try {
    c.set_force_factor(-1.0);
    FAIL() << "a negative force factor must be refused";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_STREQ(e.what(), "set_force_factor: force factor: between 0.001 and 1000");
  }
  EXPECT_THROW(c.set_base_frame({0, 0, 0, 0, 0, 0, 0}), ClientError);
  EXPECT_TRUE(
      ControllerStack::eventually([&] { return stack.link_stats().params_applied == 12U; }, 1s));
}

TEST(ConnectionParameters, PowerAndEmergencyStopRoundTrip) {
  ControllerStack stack("power");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Connection c(address_of(stack));
  c.set_power(true);
  EXPECT_TRUE(ControllerStack::eventually([&] { return c.snapshot().powered(); }));
  c.emergency_stop();
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return c.snapshot().emergency_stop() && !c.snapshot().powered(); }));
  c.reset_emergency_stop();
  c.set_power(true);
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return !c.snapshot().emergency_stop() && c.snapshot().powered(); }));
  c.set_power(false);
  EXPECT_TRUE(ControllerStack::eventually([&] { return !c.snapshot().powered(); }));
}

}  // namespace
}  // namespace hapticctrl::client
