// Tests of impairment.hpp: the network model of `hapticctrl-netem`, the project's user-space
// network impairment relay (this kernel has no netem qdisc: ../shared/PITFALLS.md).
#include "hapticctrl/netem/impairment.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::netem {
namespace {

using namespace std::chrono_literals;

/// The moment `t` after the clock's origin.
TimePoint at(Duration t) {
  return TimePoint{t};
}

TEST(Impairment, DelaysEveryDatagramAndKeepsTheirOrder) {
  LinkModel m;
  m.delay = 5ms;
  m.jitter = 2ms;
  Impairment link(m, 3);
  TimePoint last{};
  for (int i = 0; i < 1000; ++i) {
    const Duration now = i * 250us;  // 4 kHz: jitter would reorder
    const Verdict v = link.on_datagram(at(now), now);
    ASSERT_EQ(v.fate, Verdict::Fate::kDeliver);
    EXPECT_GE(v.deliver_at, at(now + 3ms));
    EXPECT_LE(v.deliver_at, std::max(last, at(now + 7ms)));
    EXPECT_GE(v.deliver_at, last) << "first in, first out";
    last = v.deliver_at;
  }
}

TEST(Impairment, ReorderingIsAllowedOnlyWhenAsked) {
  LinkModel m;
  m.delay = 5ms;
  m.jitter = 2ms;
  m.reorder = true;
  Impairment link(m, 3);
  int reordered = 0;
  TimePoint last{};
  for (int i = 0; i < 1000; ++i) {
    const Verdict v = link.on_datagram(at(i * 250us), i * 250us);
    reordered += v.deliver_at < last ? 1 : 0;
    last = v.deliver_at;
  }
  EXPECT_GT(reordered, 100);
}

TEST(Impairment, LosesTheAskedShareAndInBurstsWhenAsked) {
  for (const double burst : {1.0, 8.0}) {
    LinkModel m;
    m.loss = 0.1;
    m.burst = burst;
    Impairment link(m, 11);
    int lost = 0;
    int runs = 0;
    bool previous_lost = false;
    constexpr int kN = 200'000;
    for (int i = 0; i < kN; ++i) {
      const bool l = link.on_datagram(at(Duration(i)), Duration(i)).fate == Verdict::Fate::kLost;
      lost += l ? 1 : 0;
      runs += l && !previous_lost ? 1 : 0;
      previous_lost = l;
    }
    EXPECT_NEAR(lost / static_cast<double>(kN), 0.1, 0.01) << "burst " << burst;
    EXPECT_NEAR(lost / static_cast<double>(runs), burst / (burst > 1 ? 1.0 : 0.9), burst * 0.15)
        << "mean burst length";
  }
}

TEST(Impairment, BlackoutsDropEverythingScheduledOrSwitched) {
  LinkModel m;
  m.blackouts.push_back(LinkModel::parse_blackout("1:0.3"));
  Impairment link(m, 1);
  EXPECT_EQ(link.on_datagram(at(0ms), 999ms).fate, Verdict::Fate::kDeliver);
  EXPECT_EQ(link.on_datagram(at(0ms), 1000ms).fate, Verdict::Fate::kBlackout);
  EXPECT_EQ(link.on_datagram(at(0ms), 1299ms).fate, Verdict::Fate::kBlackout);
  EXPECT_EQ(link.on_datagram(at(0ms), 1300ms).fate, Verdict::Fate::kDeliver);
  link.set_manual_blackout(true);
  EXPECT_EQ(link.on_datagram(at(0ms), 5000ms).fate, Verdict::Fate::kBlackout);
  link.set_manual_blackout(false);
  EXPECT_EQ(link.on_datagram(at(0ms), 5000ms).fate, Verdict::Fate::kDeliver);
}

TEST(Impairment, BadModelsAreRefusedWithTheirReason) {
  LinkModel m;
  m.loss = 1.5;
  EXPECT_THROW(Impairment(m, 1), std::invalid_argument);
  m.loss = 0.1;
  m.burst = 0.5;
  EXPECT_THROW(Impairment(m, 1), std::invalid_argument);
  for (const char* bad : {"1", "a:1", "1:0", "1:-2", "nan:1", "1:inf", ":"}) {
    EXPECT_THROW(LinkModel::parse_blackout(bad), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace hapticctrl::netem
