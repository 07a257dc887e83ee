// Tests of values.hpp: range rules for every number a peer can send.
#include "hapticctrl/protocol/values.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace hapticctrl::protocol {
namespace {

hcp_param param(hcp_param_id id) {
  hcp_param p{};
  p.id = id;
  return p;
}

TEST(Values, PosesNeedFiniteBoundedValuesAndAUnitQuaternion) {
  const double good[7] = {0.1, -0.2, 0.3, 0, 0, 0.7071068, 0.7071068};  // NOLINT
  EXPECT_FALSE(check_pose(good));
  double far[7] = {101, 0, 0, 0, 0, 0, 1};  // NOLINT
  EXPECT_TRUE(check_pose(far));
  double nan[7] = {0, 0, 0, 0, 0, 0, std::nan("")};  // NOLINT
  EXPECT_TRUE(check_pose(nan));
  double zero_q[7] = {0, 0, 0, 0, 0, 0, 0};  // NOLINT
  EXPECT_TRUE(check_pose(zero_q));
  const float single[7] = {0, 0, 0, 0, 0, 0, 1.009F};  // NOLINT: within the 2 % slack
  EXPECT_FALSE(check_pose(single));
}

TEST(Values, EachParameterHasItsRange) {
  hcp_param p = param(HCP_P_TIME_STEP);
  p.hcp_param_u.time_step = 0.001;
  EXPECT_FALSE(check_param(p));
  p.hcp_param_u.time_step = 0.0;
  EXPECT_EQ(check_param(p).value_or(""), "time step: between 1e-5 and 1 s");
  p = param(HCP_P_FORCE_FACTOR);
  p.hcp_param_u.force_factor = -1.0;
  EXPECT_TRUE(check_param(p));
  p = param(HCP_P_SPEED_FACTOR);
  p.hcp_param_u.speed_factor = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(check_param(p));
  p = param(HCP_P_INDEXING_MODE);
  p.hcp_param_u.indexing_mode = 7;  // VirtuoseAPI's: 0-4, 6 and 7
  EXPECT_FALSE(check_param(p));
  p.hcp_param_u.indexing_mode = 5;
  EXPECT_EQ(check_param(p).value_or(""), "indexing mode: 0 to 4, 6 or 7 (VirtuoseAPI's)");
  p.hcp_param_u.indexing_mode = 8;
  EXPECT_TRUE(check_param(p));
  p = param(HCP_P_BASE_FRAME_SP);
  p.hcp_param_u.base_frame_sp[6] = 1.0F;
  EXPECT_FALSE(check_param(p));
  p.hcp_param_u.base_frame_sp[6] = 2.0F;
  EXPECT_TRUE(check_param(p)) << "not a unit quaternion";
  p = param(HCP_P_COMMAND_TYPE);
  p.hcp_param_u.command_type = HCP_COMMAND_ARTICULAR_IMPEDANCE;  // 1.4's joint space
  EXPECT_FALSE(check_param(p));
  p.hcp_param_u.command_type = 5;
  EXPECT_TRUE(check_param(p));
  p = param(HCP_P_OBJECT);
  p.hcp_param_u.object = {1, 0.2, {0.001, 0.001, -0.001}};
  EXPECT_TRUE(check_param(p));
  p.hcp_param_u.object.inertia[2] = 0.001;
  EXPECT_FALSE(check_param(p));
  p = param(HCP_P_GAINS);
  p.hcp_param_u.gains[3] = -1;
  EXPECT_TRUE(check_param(p));
  p = param(HCP_P_FORCE_LIMITS);
  p.hcp_param_u.force_limits[0] = std::nan("");
  EXPECT_TRUE(check_param(p));
  p = param(HCP_P_WATCHDOG);
  p.hcp_param_u.watchdog_ms = 5;
  EXPECT_TRUE(check_param(p));
  p.hcp_param_u.watchdog_ms = 50;
  EXPECT_FALSE(check_param(p));
  EXPECT_FALSE(check_param(param(HCP_P_EMERGENCY_STOP)));
}

TEST(Values, HelloWatchdogIsZeroOrInRange) {
  hcp_hello h{};
  EXPECT_FALSE(check_hello(h));
  h.watchdog_ms = 9;
  EXPECT_TRUE(check_hello(h));
  h.watchdog_ms = 60001;
  EXPECT_TRUE(check_hello(h));
}

TEST(Values, ControlTwistAndWrenchBounds) {
  hcp_body b{};
  b.type = HCP_CONTROL_OBJECT;
  b.hcp_body_u.object.pose[6] = 1.0F;
  b.hcp_body_u.object.twist[0] = 99.0F;
  b.hcp_body_u.object.twist[5] = 999.0F;
  EXPECT_FALSE(check_control(b));
  b.hcp_body_u.object.twist[0] = 101.0F;  // linear bound is 100 m/s
  EXPECT_TRUE(check_control(b));
  b = hcp_body{};
  b.type = HCP_CONTROL_WRENCH;
  b.hcp_body_u.wrench.wrench[0] = -1001.0F;
  EXPECT_TRUE(check_control(b));
}

TEST(Values, AContactMustBeASurface) {
  const auto contact = [](const std::function<void(hcp_control_contact&)>& edit) {
    hcp_control_contact c{};
    c.slots = pack_contact_slots(0, 1);
    c.contact.normal[2] = 1.0F;
    c.contact.stiffness = 1000.0F;
    c.contact.friction[0] = 0.5F;
    c.contact.friction[1] = 0.5F;
    edit(c);
    return c;
  };
  EXPECT_FALSE(check_contact(contact([](hcp_control_contact&) {})));
  const std::vector<std::pair<const char*, std::function<void(hcp_control_contact&)>>> bad{
      {"normal not unit", [](hcp_control_contact& c) { c.contact.normal[2] = 0.5F; }},
      {"normal NaN",
       [](hcp_control_contact& c) {
         c.contact.normal[0] = std::numeric_limits<float>::quiet_NaN();
       }},
      {"point far", [](hcp_control_contact& c) { c.contact.point[1] = 1e3F; }},
      {"gap beyond 1 m", [](hcp_control_contact& c) { c.contact.distance = 2.0F; }},
      {"no stiffness", [](hcp_control_contact& c) { c.contact.stiffness = 0.0F; }},
      {"stiffness inf",
       [](hcp_control_contact& c) {
         c.contact.stiffness = std::numeric_limits<float>::infinity();
       }},
      {"negative damping", [](hcp_control_contact& c) { c.contact.damping = -1.0F; }},
      {"dynamic over static", [](hcp_control_contact& c) { c.contact.friction[1] = 0.6F; }},
      {"slot at the count", [](hcp_control_contact& c) { c.slots = pack_contact_slots(1, 1); }},
      {"nine slots", [](hcp_control_contact& c) { c.slots = pack_contact_slots(0, 9); }},
      {"reserved bits", [](hcp_control_contact& c) { c.slots |= 1U << 20U; }},
  };
  for (const auto& [why, edit] : bad) {
    EXPECT_TRUE(check_contact(contact(edit))) << why;
  }
  // A count of 0 clears every slot: its contact is not looked at.
  EXPECT_FALSE(check_contact(contact([](hcp_control_contact& c) {
    c.slots = pack_contact_slots(0, 0);
    c.contact.stiffness = 0.0F;
  })));
}

}  // namespace
}  // namespace hapticctrl::protocol
