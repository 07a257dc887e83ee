// Tests of the servo law's coupling half (servo_law_coupling.cpp): the IMPEDANCE wrench and the
// VIRTMECH spring-damper on the handle, and the fade of a silent link or an ended session.
#include "hapticctrl/rt_core/servo_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/law_inputs.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::chain_at;
using test::coupled_to_object_ahead;
using test::default_dynamics;
using test::kReady;
using test::powered_at;

TEST(ServoLaw, ImpedanceWrenchReachesTheJointsThroughTheJacobianAfterTheRamp) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.client.session_id = 1;
  in.client.command = ClientCommand::kImpedance;
  in.client.impedance_wrench = {0, 0, -10, 1, 0, 0};
  in.client_valid = true;
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_NEAR(out.rendered_wrench.head<3>().norm(), 10.0 / 50.0, 1e-9)
      << "a new session engages through the 50 ms ramp";
  for (int k = 0; k < 60; ++k) {
    law.compute(in, false, out);
  }
  const ChainState s = chain_at(kReady);
  const Vector6d expected =
      default_dynamics().gravity_torque(s) +
      default_dynamics().jacobian(s).transpose() * (Vector6d() << 0, 0, -10, 1, 0, 0).finished();
  EXPECT_LT((out.commands.torque - expected).norm(), 1e-9);
}

TEST(ServoLaw, VirtmechPullsTheHandleTowardTheObjectAndReturnsTheOpposite) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  // The handle frame is the identity rotation at the ready pose (pitches cancel).
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {  // through the engagement ramp
    law.compute(in, false, out);
  }
  EXPECT_TRUE(out.coupled);
  EXPECT_NEAR(out.rendered_wrench(0), 4.0, 1e-6) << "2000 N/m x 2 mm";
  EXPECT_NEAR(out.object_wrench(0), -4.0, 1e-6);
}

TEST(ServoLaw, VirtmechWithoutAnAttachedObjectRendersNothing) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  in.client.object_attached = false;  // virtDetachVO
  ServoOutputs out;
  for (int k = 0; k < 50; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_TRUE(out.rendered_wrench.isZero());
  EXPECT_TRUE(out.object_wrench.isZero());
}

TEST(ServoLaw, ASilentLinkFadesTheForceOutWithin50msAtMost1NPerMs) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.0175);  // 35 N: the device's peak
  ServoOutputs out;
  for (int k = 0; k < 800; ++k) {  // the spring restarts relaxed and regains 1.75 cm at 5 cm/s
    law.compute(in, false, out);
  }
  ASSERT_NEAR(out.rendered_wrench(0), 35.0, 1e-6);
  double previous = out.rendered_wrench(0);
  double max_step = 0.0;
  for (int silent_ms = 1; silent_ms <= 100; ++silent_ms) {
    in.client_silence = silent_ms * 1ms;
    in.client_age = in.client_silence;
    law.compute(in, false, out);
    max_step = std::max(max_step, std::abs(out.rendered_wrench(0) - previous));
    previous = out.rendered_wrench(0);
    if (silent_ms == 8) {
      EXPECT_NEAR(out.rendered_wrench(0), 35.0, 1e-6) << "held (extrapolated) before the fade";
      EXPECT_TRUE(out.client_stale);
    }
    if (silent_ms == 50) {
      EXPECT_EQ(out.rendered_wrench(0), 0.0) << "zero within 50 ms of the last fresh sample";
      EXPECT_EQ(out.object_wrench(0), 0.0);
    }
  }
  EXPECT_LE(max_step, 1.0 + 1e-9) << "never a step beyond 1 N per ms while fading";
  // Fresh samples again: the spring restarts relaxed where the handle is and regains its
  // stretch at 8 cm/s (2000 N/m: 0.16 N per ms), never in one step.
  in.client_silence = 0ns;
  in.client_age = 0ns;
  previous = 0.0;
  max_step = 0.0;
  for (int k = 0; k < 800; ++k) {
    law.compute(in, false, out);
    max_step = std::max(max_step, std::abs(out.rendered_wrench(0) - previous));
    previous = out.rendered_wrench(0);
  }
  EXPECT_NEAR(out.rendered_wrench(0), 35.0, 1e-6);
  // k x 8 cm/s = 0.16 N/ms, doubled at most while the engagement ramp multiplies it.
  EXPECT_LE(max_step, 2.0 * 2000.0 * 0.08 * 1e-3 + 1e-9) << "the stretch comes back at 8 cm/s";
}

TEST(ServoLaw, ASilentLinkFadesASmallForceAsLateAsTheSlopeAllowsAndAnyForceWithin45ms) {
  // 5 N is held through a 30 ms gap (a stall of the link's processes is no reason to drop the
  // weight the handle carries) and still reaches zero by 45 ms, over 15 ms; a spring
  // stretched to twice the peak (saturated at 35 N) is zero by 45 ms too.
  for (const double stretch : {0.0025, 0.035}) {
    ServoLaw law(default_dynamics());
    ServoInputs in = coupled_to_object_ahead(stretch);
    ServoOutputs out;
    for (int k = 0; k < 800; ++k) {  // restarted relaxed: the stretch comes back at 5 cm/s
      law.compute(in, false, out);
    }
    const double held = out.rendered_wrench(0);
    double previous = held;
    double max_step = 0.0;
    for (int silent_ms = 1; silent_ms <= 60; ++silent_ms) {
      in.client_silence = silent_ms * 1ms;
      in.client_age = in.client_silence;
      law.compute(in, false, out);
      max_step = std::max(max_step, std::abs(out.rendered_wrench(0) - previous));
      previous = out.rendered_wrench(0);
      if (silent_ms == 30 && stretch < 0.01) {
        EXPECT_NEAR(out.rendered_wrench(0), held, 1e-9) << "5 N held through 30 ms of silence";
        EXPECT_EQ(out.fade, 1.0);
      }
      if (silent_ms == 40) {
        EXPECT_NEAR(out.object_wrench(0), -held, 1e-6)
            << "the object keeps its spring while the hand's force fades (as through a brake)";
      }
      if (silent_ms >= 45) {
        EXPECT_NEAR(out.rendered_wrench(0), 0.0, 1e-9) << silent_ms << " ms, " << held << " N held";
      }
    }
    EXPECT_NEAR(held, stretch < 0.01 ? 5.0 : 35.0, 1e-6);
    // 5 N fades over the shortest fade (15 ms), not in a few cycles at the full-scale slope.
    EXPECT_LE(max_step, (stretch < 0.01 ? 5.0 / 15.0 : 1.0) + 1e-9) << held << " N held";
  }
}

TEST(ServoLaw, AnEndedSessionReleasesTheForceAt1NPerMs) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.0175);
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {
    law.compute(in, false, out);
  }
  in.client.session_id = 0;  // the bridge ended the session
  double previous = out.rendered_wrench(0);
  for (int k = 0; k < 40; ++k) {
    law.compute(in, false, out);
    EXPECT_LE(std::abs(out.rendered_wrench(0) - previous), 1.0 + 1e-9);
    previous = out.rendered_wrench(0);
  }
  EXPECT_EQ(out.rendered_wrench(0), 0.0);
}

}  // namespace
}  // namespace hapticctrl::rt_core
