// MuJoCo's solref/solimp as the controller's contact spring and damper (contact_mapping.hpp):
// the formula per row and per contact, and the per-surface totals the client reports.
#include "hapticctrl/mujoco/contact_mapping.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace hapticctrl::mujoco {
namespace {

/// A contact of a `mass` kg body on the world (its inverse weight alone), 1 mm deep, normal +z
/// from the world (geom1) to the body (geom2), MuJoCo's default solref and a constant
/// impedance d = 0.9.
EngineContact resting(double mass, int condim = 1, double mu = 0.5) {
  EngineContact c;
  c.distance = -0.001;
  c.normal = {0, 0, 1};
  c.body_is_geom2 = true;
  c.condim = condim;
  c.pyramidal = true;
  c.friction = {mu, mu, 0.005, 0.0001, 0.0001};
  c.inverse_weight = 1.0 / mass;
  c.solref = {0.02, 1.0};
  c.solimp = {0.9, 0.9, 0.001, 0.5, 2.0};
  return c;
}

constexpr double kStep = 0.001;

TEST(ContactGains, OneRowIsTheImpedanceTimesTheReferenceSpringTimesTheMass) {
  // k = 1 / (dmax^2 tc^2 zeta^2) = 3086.4 /s^2; K = d^2 / (1 - d) k m = 8.1 * 3086.4 * 0.5.
  const SurfaceGains g = contact_gains(resting(0.5), kStep);
  const double k = 1.0 / (0.81 * 0.02 * 0.02);
  EXPECT_NEAR(g.stiffness, 0.81 / 0.1 * k * 0.5, 1e-9 * g.stiffness);
  EXPECT_NEAR(g.damping, 0.9 / 0.1 * (2.0 / (0.9 * 0.02)) * 0.5, 1e-9 * g.damping);
  EXPECT_NEAR(g.stiffness, 12500.0, 1e-6);
}

TEST(ContactGains, APyramidHasTwoEdgesPerFrictionDirectionEachWeightedByOnePlusMuSquared) {
  const double one_row = contact_gains(resting(0.5, 1), kStep).stiffness;
  const SurfaceGains pyramid = contact_gains(resting(0.5, 3, 0.5), kStep);
  EXPECT_NEAR(pyramid.stiffness, one_row * 4.0 / 1.25, 1e-9 * one_row);
  // An elliptic cone (or condim 1) keeps the one normal row.
  EngineContact elliptic = resting(0.5, 3, 0.5);
  elliptic.pyramidal = false;
  EXPECT_NEAR(contact_gains(elliptic, kStep).stiffness, one_row, 1e-9 * one_row);
}

TEST(ContactGains, NegativeSolrefIsADirectStiffnessAndDamping) {
  EngineContact c = resting(2.0);
  c.solref = {-4000.0, -20.0};
  const SurfaceGains g = contact_gains(c, kStep);
  EXPECT_NEAR(g.stiffness, 0.81 / 0.1 * 4000.0 / 0.81 * 2.0, 1e-6);
  EXPECT_NEAR(g.damping, 0.9 / 0.1 * 20.0 / 0.9 * 2.0, 1e-9);
}

TEST(ContactGains, ATimeConstantUnderTwoStepsIsTwoSteps) {
  EngineContact fast = resting(0.5);
  fast.solref = {0.0005, 1.0};
  EngineContact two_steps = resting(0.5);
  two_steps.solref = {0.002, 1.0};
  EXPECT_DOUBLE_EQ(contact_gains(fast, kStep).stiffness, contact_gains(two_steps, kStep).stiffness);
}

TEST(ContactGains, DegenerateParametersGiveNoSpring) {
  for (const double dmin : {0.0, 1.0, -0.1, std::nan("")}) {
    EngineContact c = resting(0.5);
    c.solimp[0] = dmin;
    EXPECT_EQ(contact_gains(c, kStep).stiffness, 0.0) << dmin;
  }
  EngineContact weightless = resting(0.5);
  weightless.inverse_weight = 0.0;
  EXPECT_EQ(contact_gains(weightless, kStep).stiffness, 0.0);
  EngineContact no_rows = resting(0.5);
  no_rows.condim = 0;
  EXPECT_EQ(contact_gains(no_rows, kStep).stiffness, 0.0);
}

TEST(ToClientContacts, EachCornerOfASurfaceCarriesTheWholeSurfacesSpring) {
  // A box on a table touches at four corners: the hand feels the four rows' spring together.
  std::vector<EngineContact> corners(4, resting(0.5));
  const double one = contact_gains(corners[0], kStep).stiffness;
  std::array<client::Contact, 8> out{};
  ASSERT_EQ(to_client_contacts(corners, kStep, 0.0, out), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(out[i].stiffness, 4.0 * one, 1e-6 * one);
    EXPECT_DOUBLE_EQ(out[i].normal[2], 1.0);
  }
}

TEST(ToClientContacts, AWallAtRightAnglesIsASurfaceOfItsOwn) {
  std::vector<EngineContact> in{resting(0.5), resting(0.5)};
  in[1].normal = {1, 0, 0};
  const double one = contact_gains(in[0], kStep).stiffness;
  std::array<client::Contact, 8> out{};
  ASSERT_EQ(to_client_contacts(in, kStep, 0.0, out), 2U);
  EXPECT_NEAR(out[0].stiffness, one, 1e-6 * one);
  EXPECT_NEAR(out[1].stiffness, one, 1e-6 * one);
}

TEST(ToClientContacts, TheNormalIsHowTheSurfacePushesTheBodyAndThePointIsOnTheBody) {
  EngineContact c = resting(0.5);
  c.body_is_geom2 = false;  // the body is geom1: the surface pushes it against the normal
  c.midpoint = {0.1, 0.2, 0.0};
  c.distance = 0.004;  // 4 mm apart: the body's surface 2 mm from the midpoint
  std::array<client::Contact, 1> out{};
  ASSERT_EQ(to_client_contacts(std::span(&c, 1), kStep, 0.0, out), 1U);
  EXPECT_DOUBLE_EQ(out[0].normal[2], -1.0);
  EXPECT_NEAR(out[0].point[2], -0.002, 1e-12);
  EXPECT_DOUBLE_EQ(out[0].distance, 0.004);
}

TEST(ToClientContacts, StiffnessIsClampedToTheDeviceAndFrictionToTheProtocol) {
  EngineContact c = resting(0.5, 1, 25.0);  // 12500 N/m, friction beyond the protocol
  std::array<client::Contact, 1> out{};
  ASSERT_EQ(to_client_contacts(std::span(&c, 1), kStep, 3000.0, out), 1U);
  EXPECT_DOUBLE_EQ(out[0].stiffness, 3000.0);
  EXPECT_DOUBLE_EQ(out[0].friction_static, 10.0);
  EXPECT_DOUBLE_EQ(out[0].friction_dynamic, 10.0);
}

TEST(ToClientContacts, ContactsWithoutASpringAreLeftOutAndTheOutputIsBounded) {
  std::vector<EngineContact> in(5, resting(0.5));
  in[1].solimp[0] = 0.0;
  std::array<client::Contact, 3> out{};
  EXPECT_EQ(to_client_contacts(in, kStep, 0.0, out), 3U);
  std::array<client::Contact, 8> roomy{};
  EXPECT_EQ(to_client_contacts(in, kStep, 0.0, roomy), 4U);
}

}  // namespace
}  // namespace hapticctrl::mujoco
