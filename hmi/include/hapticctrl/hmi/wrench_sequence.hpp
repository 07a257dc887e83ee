#pragma once
/// @file wrench_sequence.hpp
/// A pre-computed operator force/torque sequence (the seeds' "pre-computed sequence"), loaded
/// and validated before anything is played.
///
/// File format: one sample per line, `t fx fy fz tx ty tz` separated by spaces, tabs or commas;
/// t in seconds from the start (strictly increasing, first >= 0), forces in N, torques in N.m
/// (base frame, at the handle). Blank lines, `#` comments and one header line are allowed.
/// Between samples the wrench is interpolated linearly; before the first sample it is zero,
/// after the last it stays at the last sample's value until the sequence ends.
#include <string>
#include <vector>

#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::hmi {

struct WrenchSample {
  double t = 0.0;
  shm::Vector6 wrench{};
};

class WrenchSequence {
 public:
  /// Parses `text`; every value must be finite and within `limits`. Throws std::invalid_argument
  /// naming `source` and the line.
  static WrenchSequence parse(const std::string& text, const std::string& source,
                              const shm::ForceLimits& limits = {});
  /// Reads and parses a file. Throws std::invalid_argument (unreadable file, bad content).
  static WrenchSequence load(const std::string& path, const shm::ForceLimits& limits = {});

  /// The wrench at `t` seconds from the start. Allocation-free.
  [[nodiscard]] shm::Vector6 at(double t) const noexcept;
  /// Time of the last sample (s).
  [[nodiscard]] double duration() const noexcept { return samples_.back().t; }
  [[nodiscard]] const std::vector<WrenchSample>& samples() const noexcept { return samples_; }

 private:
  std::vector<WrenchSample> samples_;
};

}  // namespace hapticctrl::hmi
