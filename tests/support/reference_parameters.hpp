#pragma once
/// One set of session parameters that tests apply (through frames or through the client API)
/// and then expect to find in VPr, field by field.
#include <gtest/gtest.h>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::test {

/// time step 2 ms, force factor 0.5, speed factor 2, base frame z 0.1, observation frame x -0.1,
/// indexing TRANSLATION, VIRTMECH, object attached 0.3 kg / {0.001, 0.002, 0.003}, k_lin 800,
/// force limit 10 N, watchdog 300 ms.
inline void expect_reference_parameters(const shm::VprPayload& v) {
  EXPECT_DOUBLE_EQ(v.client_time_step, 0.002);
  EXPECT_DOUBLE_EQ(v.force_factor, 0.5);
  EXPECT_DOUBLE_EQ(v.speed_factor, 2.0);
  // Frames travel in single precision from a 1.2 client (0.1 becomes 0.10000000149).
  EXPECT_NEAR(v.base_frame[2], 0.1, 1e-7);
  EXPECT_NEAR(v.observation_frame[0], -0.1, 1e-7);
  EXPECT_EQ(v.indexing_mode, 1U);
  EXPECT_EQ(v.command_type, 2U);
  EXPECT_NE(v.flags & shm::vpr_flags::kObjectAttached, 0U);
  EXPECT_DOUBLE_EQ(v.object_mass, 0.3);
  EXPECT_DOUBLE_EQ(v.object_inertia[2], 0.003);
  EXPECT_DOUBLE_EQ(v.gain_override[0], 800.0);
  EXPECT_DOUBLE_EQ(v.force_limits[0], 10.0);
  EXPECT_EQ(v.watchdog_timeout_us, 300'000U);
}

}  // namespace hapticctrl::test
