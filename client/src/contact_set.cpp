// Implements contact_set.hpp: the object's contacts, checked, in wire form, sent slot by slot.
#include "contact_set.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::client {
namespace {

hcp_contact wire_contact(const Contact& c) noexcept {
  hcp_contact w{};
  protocol::to_wire(c.point, w.point);
  protocol::to_wire(c.normal, w.normal);
  w.distance = static_cast<float>(c.distance);
  w.stiffness = static_cast<float>(c.stiffness);
  w.damping = static_cast<float>(c.damping);
  w.friction[0] = static_cast<float>(c.friction_static);
  w.friction[1] = static_cast<float>(c.friction_dynamic);
  return w;
}

bool same_contact(const hcp_contact& a, const hcp_contact& b) noexcept {
  return std::equal(std::begin(a.point), std::end(a.point), std::begin(b.point)) &&
         std::equal(std::begin(a.normal), std::end(a.normal), std::begin(b.normal)) &&
         a.distance == b.distance && a.stiffness == b.stiffness && a.damping == b.damping &&
         a.friction[0] == b.friction[0] && a.friction[1] == b.friction[1];
}

}  // namespace

ContactResult ContactSet::set(std::span<const Contact> contacts, double max_stiffness) noexcept {
  if (contacts.size() > kMaxContacts) {
    return ContactResult::kTooMany;
  }
  const auto count = static_cast<std::uint32_t>(contacts.size());
  std::array<hcp_contact, kMaxContacts> next{};
  for (std::uint32_t i = 0; i < count; ++i) {
    hcp_control_contact frame{};
    frame.slots = protocol::pack_contact_slots(i, count);
    frame.contact = wire_contact(contacts[i]);
    if (protocol::check_contact(frame)) {
      return ContactResult::kInvalid;
    }
    if (max_stiffness > 0.0 && static_cast<double>(frame.contact.stiffness) > max_stiffness) {
      return ContactResult::kTooStiff;
    }
    next[i] = frame.contact;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    changed_[i] = i >= count_ || !same_contact(next[i], contacts_[i]);
  }
  clear_due_ = count == 0 && count_ > 0;
  if (count != count_) {
    changed_.fill(true);  // every frame carries the count
  }
  contacts_ = next;
  count_ = count;
  return ContactResult::kAccepted;
}

std::optional<ContactSend> ContactSet::due(TimePoint now) noexcept {
  if (clear_due_) {
    clear_due_ = false;
    return ContactSend{protocol::pack_contact_slots(0, 0), {}};
  }
  for (std::uint32_t i = 0; i < count_; ++i) {
    if (!changed_[i] && now - sent_[i] < kRefresh) {
      continue;
    }
    changed_[i] = false;
    sent_[i] = now;
    return ContactSend{protocol::pack_contact_slots(i, count_), contacts_[i]};
  }
  return std::nullopt;
}

double ContactSet::penetration_along(const std::array<double, 3>& normal) const noexcept {
  const double length = std::hypot(normal[0], normal[1], normal[2]);
  double deepest = 0.0;
  for (std::uint32_t i = 0; i < count_ && length > 1e-6; ++i) {
    const hcp_contact& c = contacts_[i];
    const double along = (static_cast<double>(c.normal[0]) * normal[0] +
                          static_cast<double>(c.normal[1]) * normal[1] +
                          static_cast<double>(c.normal[2]) * normal[2]) /
                         length;
    if (along > 0.9) {
      deepest = std::max(deepest, -static_cast<double>(c.distance));
    }
  }
  return deepest;
}

}  // namespace hapticctrl::client
