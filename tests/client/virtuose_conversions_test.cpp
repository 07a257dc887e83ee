// The C API's conversions: a pose to a homogeneous matrix and back, a colour to grey.
#include <gtest/gtest.h>

#include <cmath>

#include "hapticctrl/virtuose_api.h"

namespace {

TEST(VirtuoseConversions, APoseMakesARowMajorHomogeneousMatrixAndComesBack) {
  const float s = std::sin(0.25F);  // a 0.5 rad turn about z
  const float c = std::cos(0.25F);
  float pose[7] = {0.1F, -0.2F, 0.3F, 0, 0, s, c};  // NOLINT(*-avoid-c-arrays)
  float m[16] = {};                                 // NOLINT(*-avoid-c-arrays)
  ASSERT_EQ(virtConvertDeplToHomogeneMatrix(nullptr, pose, m), 0);
  EXPECT_NEAR(m[0], std::cos(0.5F), 1e-6F);
  EXPECT_NEAR(m[1], -std::sin(0.5F), 1e-6F) << "row-major: m[1] is R(0, 1)";
  EXPECT_NEAR(m[4], std::sin(0.5F), 1e-6F);
  EXPECT_FLOAT_EQ(m[3], 0.1F);
  EXPECT_FLOAT_EQ(m[7], -0.2F);
  EXPECT_FLOAT_EQ(m[11], 0.3F);
  EXPECT_FLOAT_EQ(m[15], 1.0F);
  EXPECT_FLOAT_EQ(m[12], 0.0F);
  float back[7] = {};  // NOLINT(*-avoid-c-arrays)
  ASSERT_EQ(virtConvertHomogeneMatrixToDepl(nullptr, back, m), 0);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(back[i], pose[i], 1e-6F) << i;
  }
  // VirtuoseAPI's other names.
  EXPECT_EQ(virtConvertDisplToTransformationMatrix(nullptr, pose, m), 0);
  EXPECT_EQ(virtConvertTransformationMatrixToDispl(nullptr, back, m), 0);
}

TEST(VirtuoseConversions, WhatIsNotARotationIsRefusedWithIncorrectValue) {
  float pose[7] = {0, 0, 0, 0, 0, 0, 2};  // NOLINT(*-avoid-c-arrays)
  float m[16] = {};                       // NOLINT(*-avoid-c-arrays)
  EXPECT_EQ(virtConvertDeplToHomogeneMatrix(nullptr, pose, m), -1);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INCORRECT_VALUE);
  m[0] = 2.0F;  // a scaled 3x3 part
  m[5] = 1.0F;
  m[10] = 1.0F;
  EXPECT_EQ(virtConvertHomogeneMatrixToDepl(nullptr, pose, m), -1);
  EXPECT_EQ(virtGetErrorCode(nullptr), VIRT_E_INCORRECT_VALUE);
  m[0] = -1.0F;  // a reflection
  EXPECT_EQ(virtConvertHomogeneMatrixToDepl(nullptr, pose, m), -1);
  EXPECT_EQ(virtConvertHomogeneMatrixToDepl(nullptr, nullptr, m), -1);
}

TEST(VirtuoseConversions, GreyIsTheRec601Luma) {
  float rgb[3] = {1.0F, 0.5F, 0.0F};  // NOLINT(*-avoid-c-arrays)
  float gray = -1.0F;
  ASSERT_EQ(virtConvertRGBToGrayscale(nullptr, rgb, &gray), 0);
  EXPECT_NEAR(gray, 0.299F + 0.5F * 0.587F, 1e-6F);
  EXPECT_EQ(virtConvertRGBToGrayscale(nullptr, rgb, nullptr), -1);
}

}  // namespace
