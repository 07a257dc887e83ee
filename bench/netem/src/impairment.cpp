// Implements impairment.hpp: the network model of `hapticctrl-netem`, the project's user-space
// network impairment relay (this kernel has no netem qdisc: ../shared/PITFALLS.md).
#include "hapticctrl/netem/impairment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hapticctrl::netem {
namespace {

double seconds_of(const std::string& text, const std::string& whole) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value) || value < 0.0 ||
      value > 86400.0) {
    throw std::invalid_argument("blackout '" + whole +
                                "': expected AT:DURATION in seconds, each 0..86400");
  }
  return value;
}

}  // namespace

void LinkModel::validate() const {
  constexpr Duration kLongest = std::chrono::seconds(10);
  if (delay < Duration::zero() || jitter < Duration::zero() || delay > kLongest ||
      jitter > kLongest) {
    throw std::invalid_argument("delay and jitter must be 0..10 s");
  }
  if (!std::isfinite(loss) || loss < 0.0 || loss > 1.0) {
    throw std::invalid_argument("loss must be a fraction from 0 to 1");
  }
  if (!std::isfinite(burst) || burst < 1.0 || burst > 1e6) {
    throw std::invalid_argument("burst must be a mean length of 1 to 1e6 datagrams");
  }
  for (const Blackout& b : blackouts) {
    if (b.start < Duration::zero() || b.duration <= Duration::zero()) {
      throw std::invalid_argument("a blackout needs a start >= 0 and a duration > 0");
    }
  }
}

Blackout LinkModel::parse_blackout(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) {
    throw std::invalid_argument("blackout '" + text + "': expected AT:DURATION in seconds");
  }
  Blackout b;
  b.start = from_seconds(seconds_of(text.substr(0, colon), text));
  b.duration = from_seconds(seconds_of(text.substr(colon + 1), text));
  if (b.duration <= Duration::zero()) {
    throw std::invalid_argument("blackout '" + text + "': the duration must be > 0");
  }
  return b;
}

Impairment::Impairment(const LinkModel& model, std::uint64_t seed) : model_(model), random_(seed) {
  model_.validate();
  // Gilbert model: a burst ends with probability 1/burst per datagram; bursts start so that the
  // long-run share of datagrams spent in bursts equals the loss rate.
  leave_burst_ = 1.0 / model_.burst;
  enter_burst_ = model_.loss >= 1.0 ? 1.0 : model_.loss * leave_burst_ / (1.0 - model_.loss);
}

bool Impairment::in_blackout(Duration since_start) const noexcept {
  if (manual_blackout_) {
    return true;
  }
  return std::any_of(model_.blackouts.begin(), model_.blackouts.end(), [&](const Blackout& b) {
    return since_start >= b.start && since_start < b.start + b.duration;
  });
}

bool Impairment::lose() noexcept {
  if (model_.loss <= 0.0) {
    return false;
  }
  if (model_.burst <= 1.0) {
    return unit_(random_) < model_.loss;  // independent losses
  }
  bad_state_ = bad_state_ ? unit_(random_) >= leave_burst_ : unit_(random_) < enter_burst_;
  return bad_state_;
}

Verdict Impairment::on_datagram(TimePoint now, Duration since_start) {
  Verdict v;
  if (in_blackout(since_start)) {
    v.fate = Verdict::Fate::kBlackout;
    return v;
  }
  if (lose()) {
    v.fate = Verdict::Fate::kLost;
    return v;
  }
  Duration delay = model_.delay;
  if (model_.jitter > Duration::zero()) {
    const double u = unit_(random_) * 2.0 - 1.0;
    const Duration shift(
        static_cast<Duration::rep>(u * static_cast<double>(model_.jitter.count())));
    delay = std::max(Duration::zero(), delay + shift);
  }
  v.deliver_at = now + delay;
  if (!model_.reorder) {
    v.deliver_at = std::max(v.deliver_at, last_delivery_);
    last_delivery_ = v.deliver_at;
  }
  return v;
}

}  // namespace hapticctrl::netem
