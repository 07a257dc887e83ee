// Tests of client/src/contact_set.hpp alone: contacts checked as the controller checks them, sent
// slot by slot when changed or due for refresh, a clear after the last one is taken away, and the
// penetration along the controller's contact normal.
#include "contact_set.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::client {
namespace {

Contact floor_contact(double distance, double stiffness = 2000.0) {
  Contact c;
  c.point = {0.1, 0.0, 0.0};
  c.normal = {0.0, 0.0, 1.0};
  c.distance = distance;
  c.stiffness = stiffness;
  c.damping = 5.0;
  c.friction_static = 0.5;
  c.friction_dynamic = 0.4;
  return c;
}

Contact wall_contact() {
  Contact c = floor_contact(-0.004);
  c.normal = {1.0, 0.0, 0.0};
  return c;
}

protocol::ContactSlots slots_of(const ContactSend& s) {
  return protocol::contact_slots(s.slots);
}

TEST(ContactSet, RefusesWhatTheControllerWouldRefuseAndKeepsTheLastSet) {
  ContactSet set;
  const std::array<Contact, 1> one{floor_contact(-0.002)};
  ASSERT_EQ(set.set(one, 0.0), ContactResult::kAccepted);

  Contact bent = floor_contact(-0.001);
  bent.normal = {0.0, 0.5, 0.5};  // not a unit vector
  const std::array<Contact, 1> invalid{bent};
  EXPECT_EQ(set.set(invalid, 0.0), ContactResult::kInvalid);
  const std::array<Contact, 1> stiff{floor_contact(-0.001, 5000.0)};
  EXPECT_EQ(set.set(stiff, 3000.0), ContactResult::kTooStiff);
  EXPECT_EQ(set.set(stiff, 0.0), ContactResult::kAccepted);  // 0: no controller limit known
  std::array<Contact, kMaxContacts + 1> many{};
  many.fill(floor_contact(0.0));
  EXPECT_EQ(set.set(many, 0.0), ContactResult::kTooMany);
  EXPECT_EQ(set.count(), 1U);
}

TEST(ContactSet, SendsEachChangedSlotOnceThenRefreshesEvery5Ms) {
  ContactSet set;
  const std::array<Contact, 2> two{floor_contact(-0.002), wall_contact()};
  ASSERT_EQ(set.set(two, 0.0), ContactResult::kAccepted);
  const TimePoint t0{std::chrono::seconds(1)};
  const std::optional<ContactSend> first = set.due(t0);
  const std::optional<ContactSend> second = set.due(t0);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(slots_of(*first).slot, 0U);
  EXPECT_EQ(slots_of(*second).slot, 1U);
  EXPECT_EQ(slots_of(*second).count, 2U);
  EXPECT_FLOAT_EQ(second->contact.normal[0], 1.0F);
  EXPECT_FALSE(set.due(t0 + std::chrono::milliseconds(1)));  // nothing changed, not yet stale

  // The same contacts again change nothing; a changed one goes out at once.
  ASSERT_EQ(set.set(two, 0.0), ContactResult::kAccepted);
  EXPECT_FALSE(set.due(t0 + std::chrono::milliseconds(2)));
  const std::array<Contact, 2> deeper{floor_contact(-0.003), wall_contact()};
  ASSERT_EQ(set.set(deeper, 0.0), ContactResult::kAccepted);
  const std::optional<ContactSend> changed = set.due(t0 + std::chrono::milliseconds(2));
  ASSERT_TRUE(changed);
  EXPECT_EQ(slots_of(*changed).slot, 0U);
  EXPECT_FALSE(set.due(t0 + std::chrono::milliseconds(2)));

  // Slot 1 was last sent at t0: stale 5 ms later, slot 0 (sent at +2 ms) not yet.
  const std::optional<ContactSend> refresh = set.due(t0 + ContactSet::kRefresh);
  ASSERT_TRUE(refresh);
  EXPECT_EQ(slots_of(*refresh).slot, 1U);
  EXPECT_FALSE(set.due(t0 + ContactSet::kRefresh));
}

TEST(ContactSet, TakingTheLastContactAwaySendsOneClear) {
  ContactSet set;
  const std::array<Contact, 1> one{floor_contact(-0.002)};
  ASSERT_EQ(set.set(one, 0.0), ContactResult::kAccepted);
  ASSERT_TRUE(set.due(TimePoint{std::chrono::milliseconds(0)}));
  ASSERT_EQ(set.set({}, 0.0), ContactResult::kAccepted);
  const std::optional<ContactSend> clear = set.due(TimePoint{std::chrono::milliseconds(1)});
  ASSERT_TRUE(clear);
  EXPECT_EQ(slots_of(*clear).count, 0U);
  EXPECT_FALSE(set.due(TimePoint{std::chrono::milliseconds(100)}));  // nothing left to refresh
}

TEST(ContactSet, PenetrationCountsContactsAlongTheNormalOnly) {
  ContactSet set;
  const std::array<Contact, 2> two{floor_contact(-0.002), wall_contact()};
  ASSERT_EQ(set.set(two, 0.0), ContactResult::kAccepted);
  EXPECT_NEAR(set.penetration_along({0.0, 0.0, 2.0}), 0.002, 1e-9);  // any length
  EXPECT_NEAR(set.penetration_along({1.0, 0.0, 0.0}), 0.004, 1e-9);  // the wall
  EXPECT_DOUBLE_EQ(set.penetration_along({0.0, 1.0, 0.0}), 0.0);     // neither
  EXPECT_DOUBLE_EQ(set.penetration_along({0.0, 0.0, 0.0}), 0.0);     // no contact normal
  const std::array<Contact, 1> apart{floor_contact(0.01)};
  ASSERT_EQ(set.set(apart, 0.0), ContactResult::kAccepted);
  EXPECT_DOUBLE_EQ(set.penetration_along({0.0, 0.0, 1.0}), 0.0);  // a gap is no penetration
}

}  // namespace
}  // namespace hapticctrl::client
