// Implements wrench_sequence.hpp: a pre-computed operator force/torque sequence (the seeds'
// "pre-computed sequence"), loaded and validated before anything is played.
#include "hapticctrl/hmi/wrench_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "number_text.hpp"

namespace hapticctrl::hmi {
namespace {

std::vector<std::string> fields_of(std::string line) {
  std::replace_if(
      line.begin(), line.end(), [](char c) { return c == ',' || c == '\t'; }, ' ');
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string f; in >> f;) {
    fields.push_back(f);
  }
  return fields;
}

}  // namespace

WrenchSequence WrenchSequence::parse(const std::string& text, const std::string& source,
                                     const shm::ForceLimits& limits) {
  WrenchSequence seq;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto where = [&] { return source + ":" + std::to_string(number) + ": "; };
    line = line.substr(0, line.find('#'));
    const std::vector<std::string> fields = fields_of(line);
    if (fields.empty()) {
      continue;
    }
    double values[7] = {};  // NOLINT(*-avoid-c-arrays)
    bool numeric = fields.size() == 7;
    for (std::size_t i = 0; numeric && i < 7; ++i) {
      numeric = parse_finite(fields[i], values[i]);
    }
    if (!numeric) {
      if (seq.samples_.empty() && !fields.empty() && !parse_finite(fields[0], values[0])) {
        continue;  // a header line ("t fx fy fz tx ty tz")
      }
      throw std::invalid_argument(where() + "expected 7 numbers: t fx fy fz tx ty tz");
    }
    WrenchSample sample;
    sample.t = values[0];
    std::copy_n(values + 1, 6, sample.wrench.begin());
    if (!std::isfinite(sample.t) || sample.t < 0.0) {
      throw std::invalid_argument(where() + "time must be finite and >= 0");
    }
    if (!seq.samples_.empty() && sample.t <= seq.samples_.back().t) {
      throw std::invalid_argument(where() + "times must increase strictly");
    }
    if (!shm::wrench_acceptable(sample.wrench, limits)) {
      throw std::invalid_argument(
          where() + "wrench must be finite, |f| <= " + std::to_string(limits.max_force) +
          " N and |t| <= " + std::to_string(limits.max_torque) + " N.m per axis");
    }
    seq.samples_.push_back(sample);
  }
  if (seq.samples_.empty()) {
    throw std::invalid_argument(source + ": no samples (format: t fx fy fz tx ty tz per line)");
  }
  return seq;
}

WrenchSequence WrenchSequence::load(const std::string& path, const shm::ForceLimits& limits) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument("cannot read sequence file '" + path + "'");
  }
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path, limits);
}

shm::Vector6 WrenchSequence::at(double t) const noexcept {
  if (!(t >= samples_.front().t)) {
    return {};
  }
  if (t >= samples_.back().t) {
    return samples_.back().wrench;
  }
  const auto next = std::upper_bound(samples_.begin(), samples_.end(), t,
                                     [](double v, const WrenchSample& s) { return v < s.t; });
  const WrenchSample& b = *next;
  const WrenchSample& a = *(next - 1);
  const double u = (t - a.t) / (b.t - a.t);
  shm::Vector6 out{};
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = a.wrench[i] + u * (b.wrench[i] - a.wrench[i]);
  }
  return out;
}

}  // namespace hapticctrl::hmi
