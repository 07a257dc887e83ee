// Tests of wrench_sequence.hpp: a pre-computed operator force/torque sequence (the seeds'
// "pre-computed sequence"), loaded and validated before anything is played.
#include "hapticctrl/hmi/wrench_sequence.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::hmi {
namespace {

std::string error_of(const std::string& text) {
  try {
    (void)WrenchSequence::parse(text, "seq");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(WrenchSequence, ParsesCommentsHeaderAndSeparatorsAndInterpolates) {
  const WrenchSequence s = WrenchSequence::parse(
      "t fx fy fz tx ty tz\n# ramp up, hold, release\n0.5, 0, 0, 0, 0, 0, 0\n"
      "1.5\t10 0 -4 0 0 0.5  # hold\n\n2.5 0 0 0 0 0 0\n",
      "seq");
  ASSERT_EQ(s.samples().size(), 3U);
  EXPECT_DOUBLE_EQ(s.duration(), 2.5);
  EXPECT_EQ(s.at(0.2), shm::Vector6{}) << "zero before the first sample";
  EXPECT_DOUBLE_EQ(s.at(1.0)[0], 5.0);
  EXPECT_DOUBLE_EQ(s.at(1.0)[2], -2.0);
  EXPECT_DOUBLE_EQ(s.at(1.5)[5], 0.5);
  EXPECT_DOUBLE_EQ(s.at(2.0)[0], 5.0);
  EXPECT_EQ(s.at(9.0), shm::Vector6{}) << "holds the last sample";
}

TEST(WrenchSequence, RejectsBadFilesNamingTheLine) {
  EXPECT_EQ(error_of(""), "seq: no samples (format: t fx fy fz tx ty tz per line)");
  EXPECT_EQ(error_of("0 1 2 3\n"), "seq:1: expected 7 numbers: t fx fy fz tx ty tz");
  EXPECT_EQ(error_of("0 0 0 0 0 0 0\nx 0 0 0 0 0 0\n"),
            "seq:2: expected 7 numbers: t fx fy fz tx ty tz");
  EXPECT_EQ(error_of("1 0 0 0 0 0 0\n1 0 0 0 0 0 0\n"), "seq:2: times must increase strictly");
  EXPECT_EQ(error_of("-1 0 0 0 0 0 0\n"), "seq:1: time must be finite and >= 0");
  EXPECT_NE(error_of("0 150 0 0 0 0 0\n").find("seq:1: wrench must be finite"), std::string::npos);
  EXPECT_EQ(error_of("0 0 0 0 0 0 nan\n"), "seq:1: expected 7 numbers: t fx fy fz tx ty tz")
      << "not a finite number";
  EXPECT_THROW((void)WrenchSequence::load("/nonexistent/seq.txt"), std::invalid_argument);
}

}  // namespace
}  // namespace hapticctrl::hmi
