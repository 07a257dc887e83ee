// The coupling gains (servo_law_gains.cpp): derived from the object and the loop delay.
#include <gtest/gtest.h>

#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "support/law_inputs.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::coupled_to_object_ahead;
using test::default_dynamics;

TEST(ServoLaw, GainsFollowObjectMassAndTimeStepWithinDeviceBounds) {
  ServoLaw law(default_dynamics());
  ClientSample c;
  c.object_mass = 0.5;
  c.time_step = 1e-3;
  CouplingGains g = law.derive_gains(c, 0.0);
  EXPECT_DOUBLE_EQ(g.k_linear, 2000.0) << "bounded by the device";
  EXPECT_DOUBLE_EQ(g.b_linear, 20.0);
  c.object_mass = 0.01;
  c.time_step = 10e-3;
  g = law.derive_gains(c, 0.0);
  EXPECT_DOUBLE_EQ(g.k_linear, 25.0) << "0.25 m / T^2";
  EXPECT_NEAR(g.b_linear, 0.7, 1e-12) << "damping ratio 0.7";
  c.gain_override = {1e6, 5.0, 0, 0};
  g = law.derive_gains(c, 0.0);
  EXPECT_DOUBLE_EQ(g.k_linear, 2000.0) << "override bounded";
  EXPECT_DOUBLE_EQ(g.b_linear, 5.0);
}

TEST(ServoLaw, GainsFallWithTheMeasuredLoopDelay) {
  // The demo's sphere: 0.5 kg, 5 cm radius inertia; 1 ms client step. With a loop of L s the
  // lag is T = 1 ms + L: k = 0.25 m / T^2 (device-bounded), angular alike with the inertia.
  ServoLaw law(default_dynamics());
  ClientSample c;
  c.object_mass = 0.5;
  c.object_inertia = {1.8e-4, 1.8e-4, 1.8e-4};
  c.time_step = 1e-3;
  const CouplingGains fast = law.derive_gains(c, 0.002);
  EXPECT_NEAR(fast.k_angular, 0.25 * 1.8e-4 / (0.003 * 0.003), 1e-9);
  const CouplingGains slow = law.derive_gains(c, 0.041);
  EXPECT_NEAR(slow.k_linear, 0.25 * 0.5 / (0.042 * 0.042), 1e-9);
  EXPECT_LT(slow.k_angular, fast.k_angular / 100.0);
  EXPECT_LT(slow.b_linear, fast.b_linear);
}

TEST(ServoLaw, TheAngularGainsAreBoundedByTheSmallestPrincipalMoment) {
  // A slender peg (J3): stable about its long axis, not only about the two others.
  ServoLaw law(default_dynamics());
  ClientSample c;
  c.object_mass = 0.1;
  c.object_inertia = {3.3e-5, 3.3e-5, 6.0e-6};
  c.time_step = 1e-3;
  const CouplingGains g = law.derive_gains(c, 0.002);
  EXPECT_NEAR(g.k_angular, 0.25 * 6.0e-6 / (0.003 * 0.003), 1e-12);
  EXPECT_LE(g.b_angular, 6.0e-6 / 0.003 + 1e-15);
  c.object_inertia = {0.0, 6.0e-6, 0.0};  // undeclared moments are not the smallest
  EXPECT_NEAR(law.derive_gains(c, 0.002).k_angular, g.k_angular, 1e-12);
}

TEST(ServoLaw, TheLoopDelayEnvelopeFollowsTheMedianUpAtOnceAndDownSlowly) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.0);
  ServoOutputs out;
  in.new_sample = true;
  const auto feed = [&](Duration loop, int samples) {
    in.loop_delay = loop;
    for (int k = 0; k < samples; ++k) {
      law.compute(in, false, out);
    }
  };
  feed(3ms, 15);
  EXPECT_EQ(out.loop_delay, 3ms);
  feed(40ms, 1);
  EXPECT_EQ(out.loop_delay, 3ms) << "one long loop (a lost answer) changes nothing";
  feed(40ms, 7);
  EXPECT_EQ(out.loop_delay, 40ms) << "a slower link lowers the gains at once";
  feed(3ms, 18);
  EXPECT_GT(out.loop_delay, 35ms) << "and they come back slowly";
  feed(3ms, 2000);
  EXPECT_LT(out.loop_delay, 4ms);
  feed(0ns, 2000);  // a client without the timing echo: the assumed loop
  EXPECT_EQ(out.loop_delay, law.config().assumed_loop_delay);
}

TEST(ServoLaw, GainsIgnoreLoopJitterWithinTheirBandDropAtOnceAndRiseSmoothly) {
  // A stretched spring steps its force with every change of k: jitter must not move the gains
  // (H1: +-2 ms at 20 ms one way jiggled the weighted sphere), a slower loop lowers them at
  // once, a faster one raises them over 50 ms.
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.0);
  in.dt = 1ms;
  in.new_sample = true;
  ServoOutputs out;
  const auto feed = [&](Duration loop) {
    in.loop_delay = loop;
    law.compute(in, false, out);
  };
  for (int k = 0; k < 15; ++k) {
    feed(40ms);
  }
  const double k40 = law.derive_gains(in.client, 0.040).k_linear;
  ASSERT_EQ(out.gains.k_linear, k40);
  for (int k = 0; k < 500; ++k) {
    feed((k % 2 == 0 ? 40 : 43) * 1ms);
    ASSERT_EQ(out.gains.k_linear, k40) << "jitter within 10 % of the design, sample " << k;
  }
  EXPECT_EQ(out.loop_delay, 40ms) << "the design delay stays";
  double largest_rise = 0.0;
  for (int k = 0; k < 5000; ++k) {
    const double before = out.gains.k_linear;
    feed(3ms);
    largest_rise = std::max(largest_rise, out.gains.k_linear / before - 1.0);
  }
  const double k_fast = law.derive_gains(in.client, to_seconds(out.loop_delay)).k_linear;
  EXPECT_NEAR(out.gains.k_linear, k_fast, 1e-6 * k_fast) << "at the faster link's design";
  EXPECT_GT(k_fast, 10.0 * k40);
  EXPECT_LT(largest_rise, 0.02) << "stiffer by 1/50 of the way per cycle (a new design: 23 %)";
  for (int k = 0; k < 8; ++k) {
    feed(40ms);
  }
  EXPECT_EQ(out.gains.k_linear, k40) << "a slower loop lowers the gains at once";
}

}  // namespace
}  // namespace hapticctrl::rt_core
