// VirtuoseAPI's indexing in the client library: a shift keeps the avatar still on the indexed
// axes while the handle moves, and releasing keeps the offset reached.
#include "indexing.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hapticctrl::client {
namespace {

constexpr double kTol = 1e-12;

Pose7 at(double x, double y, double z, double yaw = 0.0) {
  return {x, y, z, 0, 0, std::sin(yaw / 2), std::cos(yaw / 2)};
}

double yaw_of(const Pose7& p) {
  return 2.0 * std::atan2(p[5], p[6]);
}

TEST(Indexing, WithoutAShiftTheAvatarIsTheHandle) {
  Indexing ix;
  const Pose7 p = at(0.4, 0.1, 0.2, 0.3);
  const Pose7 a = ix.avatar(p);
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_NEAR(a[i], p[i], kTol);
  }
  EXPECT_FALSE(ix.shifted());
  EXPECT_FALSE(ix.forces_inhibited());
}

TEST(Indexing, AllModeFreezesTheAvatarWhileShiftedAndKeepsTheOffsetAfter) {
  Indexing ix;
  ix.press(at(0.4, 0.0, 0.2, 0.1));
  EXPECT_TRUE(ix.shifted());
  const Pose7 moved = at(0.3, 0.05, 0.2, 0.4);  // the hand moves the handle back and turns it
  const Pose7 during = ix.avatar(moved);
  EXPECT_NEAR(during[0], 0.4, kTol);
  EXPECT_NEAR(during[1], 0.0, kTol);
  EXPECT_NEAR(yaw_of(during), 0.1, 1e-9);
  const Vector6 twist = ix.avatar_twist(moved, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6});
  for (const double v : twist) {
    EXPECT_EQ(v, 0.0) << "the avatar keeps still";
  }
  ix.release(moved);
  EXPECT_FALSE(ix.shifted());
  // After: the handle moving +2 cm in x moves the avatar +2 cm from where it was held.
  const Pose7 after = ix.avatar(at(0.32, 0.05, 0.2, 0.4));
  EXPECT_NEAR(after[0], 0.42, kTol);
  EXPECT_NEAR(after[1], 0.0, kTol);
  EXPECT_NEAR(yaw_of(after), 0.1, 1e-9);
  // An object given at the avatar is where the handle is, for the controller.
  const Pose7 object = ix.to_physical(at(0.32, 0.05, 0.2, 0.4), after);
  EXPECT_NEAR(object[0], 0.32, kTol);
  EXPECT_NEAR(object[1], 0.05, kTol);
  EXPECT_NEAR(yaw_of(object), 0.4, 1e-9);
}

TEST(Indexing, TranslationModeIndexesOnlyTheTranslationAndRotationModeOnlyTheRotation) {
  Indexing ix;
  ASSERT_TRUE(ix.set_mode(1));  // INDEXING_TRANS
  ix.press(at(0.4, 0, 0.2, 0.0));
  Pose7 a = ix.avatar(at(0.3, 0, 0.2, 0.5));
  EXPECT_NEAR(a[0], 0.4, kTol);
  EXPECT_NEAR(yaw_of(a), 0.5, 1e-9) << "the rotation follows the handle";
  ix.release(at(0.3, 0, 0.2, 0.5));

  Indexing rot;
  ASSERT_TRUE(rot.set_mode(7));  // INDEXING_ROT
  rot.press(at(0.4, 0, 0.2, 0.0));
  a = rot.avatar(at(0.3, 0, 0.2, 0.5));
  EXPECT_NEAR(a[0], 0.3, kTol) << "the translation follows the handle";
  EXPECT_NEAR(yaw_of(a), 0.0, 1e-9);
  const Vector6 w = rot.to_avatar(at(0.3, 0, 0.2, 0.5), {1, 0, 0, 1, 0, 0});
  EXPECT_NEAR(w[0], 1.0, kTol) << "forces never rotate";
  EXPECT_NEAR(w[3], std::cos(-0.5), 1e-9) << "torques turn with the offset";
  EXPECT_NEAR(w[4], std::sin(-0.5), 1e-9);
}

TEST(Indexing, NoneModeNeverIndexesAndInhibitingModesStopForcesOnlyWhileShifted) {
  Indexing none;
  ASSERT_TRUE(none.set_mode(2));  // INDEXING_NONE
  none.press(at(0.4, 0, 0.2));
  EXPECT_NEAR(none.avatar(at(0.3, 0, 0.2))[0], 0.3, kTol);
  EXPECT_FALSE(none.forces_inhibited());

  Indexing inhibited;
  ASSERT_TRUE(inhibited.set_mode(3));  // INDEXING_ALL_FORCE_FEEDBACK_INHIBITION
  EXPECT_FALSE(inhibited.forces_inhibited());
  inhibited.press(at(0.4, 0, 0.2));
  EXPECT_TRUE(inhibited.forces_inhibited());
  inhibited.release(at(0.4, 0, 0.2));
  EXPECT_FALSE(inhibited.forces_inhibited());
}

TEST(Indexing, ModesOutsideVirtuoseApisAreRefused) {
  Indexing ix;
  EXPECT_FALSE(ix.set_mode(5));
  EXPECT_FALSE(ix.set_mode(8));
  EXPECT_EQ(ix.mode(), 0U);
  EXPECT_TRUE(ix.set_mode(6));
  EXPECT_EQ(ix.mode(), 6U);
}

}  // namespace
}  // namespace hapticctrl::client
