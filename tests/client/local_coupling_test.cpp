// Tests of client/src/local_coupling.cpp: the object's side of the coupling the library closes
// itself (protocol 1.3).
#include "local_coupling.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hapticctrl::client {
namespace {

CouplingTerms terms(double k, double b) {
  CouplingTerms t;
  t.gains = {k, b, 2.0, 0.1};
  t.limits = {35.0, 3.0};
  return t;
}

const Pose7 kAt{0.5, 0.0, 0.2, 0, 0, 0, 1};

TEST(LocalCoupling, TheSpringPullsTheObjectToTheHandleImage) {
  const Pose7 handle{0.51, 0.0, 0.2, 0, 0, 0, 1};
  const Vector6 w = object_wrench(terms(1000.0, 10.0), handle, {}, kAt, {}, 0.0, 1.0, 1.0);
  EXPECT_NEAR(w[0], 10.0, 1e-9);
  EXPECT_NEAR(w[1], 0.0, 1e-12);
}

TEST(LocalCoupling, TheDamperActsOnTheObjectsOwnVelocityNow) {
  const Vector6 moving{0.1, 0, 0, 0, 0, 0};
  const Vector6 w = object_wrench(terms(1000.0, 10.0), kAt, {}, kAt, moving, 0.0, 1.0, 1.0);
  EXPECT_NEAR(w[0], -1.0, 1e-9) << "b x (v_handle - v_object)";
}

TEST(LocalCoupling, SpeedFactorDescalesThePositionsAndNoForceFactorReachesTheObject) {
  const Pose7 handle{0.52, 0.0, 0.2, 0, 0, 0, 1};  // 2 cm in the client's units
  const Vector6 w = object_wrench(terms(1000.0, 0.0), handle, {}, kAt, {}, 0.0, 2.0, 3.0);
  EXPECT_NEAR(w[0], 10.0, 1e-9) << "k x 2 cm / speed factor 2";
}

TEST(LocalCoupling, TheContactStiffensOnlyWhileThePushIsIntoTheSurface) {
  CouplingTerms t = terms(100.0, 0.0);
  t.contact_normal = {-1.0, 0.0, 0.0};  // the surface pushes the object along -x
  t.normal_gains = {900.0, 0.0};
  const Pose7 pressing{0.51, 0.0, 0.2, 0, 0, 0, 1};  // the handle 1 cm into the surface
  EXPECT_NEAR(object_wrench(t, pressing, {}, kAt, {}, 0.0, 1.0, 1.0)[0], 10.0, 1e-9)
      << "(100 + 900) N/m x 1 cm";
  const Pose7 pulling{0.49, 0.0, 0.2, 0, 0, 0, 1};
  EXPECT_NEAR(object_wrench(t, pulling, {}, kAt, {}, 0.0, 1.0, 1.0)[0], -1.0, 1e-9)
      << "pulled off the surface: the free spring only";
}

TEST(LocalCoupling, TheStiffeningActsOnTheHandlesDepthInTheSurface) {
  // J2: the object 2 mm into its surface and the handle 3 mm past it: the handle is 5 mm deep in
  // the surface, and the object is pressed with what the hand feels there, 2000 N/m x 5 mm.
  CouplingTerms t = terms(100.0, 0.0);
  t.contact_normal = {-1.0, 0.0, 0.0};
  t.normal_gains = {1900.0, 0.0};
  const Pose7 pressing{0.503, 0.0, 0.2, 0, 0, 0, 1};
  EXPECT_NEAR(object_wrench(t, pressing, {}, kAt, {}, 0.002, 1.0, 1.0)[0], 2000.0 * 0.005, 1e-9);
  t.normal_gains = {0.0, 0.0};  // the coupling alone as stiff as the surface
  t.gains[0] = 2000.0;
  EXPECT_NEAR(object_wrench(t, pressing, {}, kAt, {}, 0.002, 1.0, 1.0)[0], 2000.0 * 0.005, 1e-9);
}

TEST(LocalCoupling, TheWrenchIsClampedToTheLimitsInTheApplicationsUnits) {
  const Pose7 far{1.5, 0.0, 0.2, 0, 0, 0, 1};
  const Vector6 w = object_wrench(terms(1000.0, 0.0), far, {}, kAt, {}, 0.0, 1.0, 2.0);
  EXPECT_NEAR(w[0], 17.5, 1e-9) << "35 N / force factor 2";
}

TEST(LocalCoupling, ARotationStretchGivesATorqueAboutItsAxis) {
  const double s = std::sin(0.05);
  const Pose7 turned{0.5, 0.0, 0.2, 0, 0, s, std::cos(0.05)};  // 0.1 rad about z
  const Vector6 w = object_wrench(terms(0.0, 0.0), turned, {}, kAt, {}, 0.0, 1.0, 1.0);
  EXPECT_NEAR(w[5], 0.2, 1e-9) << "2 N.m/rad x 0.1 rad";
}

TEST(LocalCoupling, TheLocalWrenchReplacesTheControllersInTheShareOfTheContactInForce) {
  CouplingTerms t;
  const Vector6 controller{4, 1, 0, 0.1, 0, 0};
  const Vector6 local{2, 0, 0, 0, 0, 0};
  EXPECT_EQ(along_contact(t, controller, local), controller) << "no contact: the controller's";
  t.contact_normal = {-1.0, 0.0, 0.0};
  EXPECT_EQ(along_contact(t, controller, local), local) << "a contact in force: the local one";
  t.contact_normal = {-0.25, 0.0, 0.0};  // a quarter in force (fading, or just touching)
  const Vector6 w = along_contact(t, controller, local);
  EXPECT_NEAR(w[0], 4.0 - 0.25 * 2.0, 1e-12);
  EXPECT_NEAR(w[1], 1.0 - 0.25 * 1.0, 1e-12);
  EXPECT_NEAR(w[3], 0.1 - 0.25 * 0.1, 1e-12);
}

}  // namespace
}  // namespace hapticctrl::client
