// Passivity (servo_law_passivity.cpp): the channel's two-port controller and the handle's guard.
#include <gtest/gtest.h>

#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "support/law_inputs.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::coupled_to_object_ahead;
using test::default_dynamics;

TEST(ServoLaw, TheChannelsPassivityControllerLetsTheImageGiveWayWhenTheClientGaveNothing) {
  // The object runs away from the handle (+x) while the client reports no energy put into the
  // channel: the coupling would draw energy out of the channel (its force on the object points
  // back, -x, against the motion). The core's PC lets the image drift towards the handle so
  // that what came out never exceeds what the client reported, and the spring softens.
  const auto run = [](double client_energy) {
    ServoLaw law(default_dynamics());
    ServoInputs in = coupled_to_object_ahead(0.005);
    in.client.object_twist = {0.2, 0, 0, 0, 0, 0};
    in.client.energy_in = client_energy;
    ServoOutputs out;
    for (int k = 0; k < 300; ++k) {
      law.compute(in, false, out);
    }
    return std::make_pair(out, law.counters().channel_pc_active);
  };
  const auto [guarded, active] = run(0.0);
  EXPECT_GT(active, 0U);
  EXPECT_LE(guarded.channel_energy_out, 1e-9) << "nothing out beyond the client's 0 J";
  const auto [free, idle] = run(100.0);  // the client reports plenty: nothing to do
  EXPECT_EQ(idle, 0U);
  EXPECT_GT(free.channel_energy_out, 0.01);
  EXPECT_LT(std::abs(guarded.handle_wrench(0)), std::abs(free.handle_wrench(0)))
      << "the image gave way: less pull on the handle";
  const auto [old_client, none] = run(-1.0);  // a 1.0 client reports nothing at all
  EXPECT_EQ(none, 0U) << "no two-port PC without the client's energy";
  EXPECT_EQ(old_client.channel_energy_out, 0.0) << "nor an account";
  EXPECT_EQ(old_client.handle_wrench(0), free.handle_wrench(0));
}

TEST(ServoLaw, ANewSessionStartsItsChannelAccountAfresh) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.005);
  in.client.object_twist = {0.2, 0, 0, 0, 0, 0};
  in.client.energy_in = 100.0;
  ServoOutputs out;
  for (int k = 0; k < 300; ++k) {
    law.compute(in, false, out);
  }
  const double before = out.channel_energy_out;
  ASSERT_GT(before, 0.1);
  in.client.session_id = 2;
  law.compute(in, false, out);
  EXPECT_LT(out.channel_energy_out, 0.01) << "one cycle's worth, not the old session's " << before;
}

TEST(ServoLaw, ThePassivityGuardsDampingDoesNotCompoundInTheRateLimiter) {
  // The guard's damping used to be stored in the wrench the rate limiter started from the next
  // cycle, so it accumulated cycle after cycle (H1).
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {
    law.compute(in, false, out);
  }
  for (int k = 0; k < 200 && law.counters().passivity_active == 0; ++k) {
    in.measures.velocity(1) = -0.01 * k;  // the handle runs along the spring's pull
    law.compute(in, false, out);
  }
  ASSERT_GT(law.counters().passivity_active, 0U);
  ASSERT_GT((out.handle_wrench + out.coupling_wrench).norm(), 1e-6) << "the guard damped";
  EXPECT_LT((law.memory().wrench + out.coupling_wrench).norm(), 1e-9)
      << "the limiter's memory holds the coupling only";
}

TEST(ServoLaw, TheObjectFeelsTheCouplingButNotThePassivityGuardsDamping) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {  // ramp the coupling up, handle at rest
    law.compute(in, false, out);
  }
  // The handle now moves along the spring's pull, faster and faster: the port gives energy
  // to the hand, the guard turns on and adds damping on the handle only.
  in.measures.velocity << 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  for (int k = 0; k < 200 && law.counters().passivity_active == 0; ++k) {
    in.measures.velocity(1) = -0.01 * k;
    law.compute(in, false, out);
  }
  ASSERT_GT(law.counters().passivity_active, 0U);
  EXPECT_TRUE(out.coupled);
  EXPECT_GT((out.handle_wrench + out.coupling_wrench).norm(), 1e-6)
      << "the handle got damping that the object did not";
}

}  // namespace
}  // namespace hapticctrl::rt_core
