#pragma once
/// @file contact_set.hpp
/// The object's contacts as the client sends them (protocol 1.3): checked as the controller
/// checks them, kept in wire form, and sent slot by slot, each when it changed or its refresh is
/// due (the controller fades a contact not refreshed in 30 ms). No socket and no clock: the
/// session asks which slot is due at `now` and frames it.
///
/// Real-time contract: every member is noexcept and allocates nothing; safe in an application's
/// physics step.

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/types.hpp"
#include "hapticctrl/protocol/codec.hpp"

namespace hapticctrl::client {

/// One CONTROL_CONTACT's content: slot and count packed, and the contact (a clear: count 0).
struct ContactSend {
  std::uint32_t slots = 0;
  hcp_contact contact{};
};

class ContactSet {
 public:
  /// Contacts are refreshed at least this often.
  static constexpr Duration kRefresh = std::chrono::milliseconds(5);

  /// The contacts from now on, each checked (protocol::check_contact) and its stiffness within
  /// `max_stiffness` (N/m; 0: no limit). Nothing changes unless every one is accepted.
  ContactResult set(std::span<const Contact> contacts, double max_stiffness) noexcept;
  /// The next slot to send at `now` (a changed or stale one, or a clear of the last set), if any;
  /// marks it sent.
  std::optional<ContactSend> due(TimePoint now) noexcept;
  /// The deepest penetration (m, >= 0) of the contacts whose normal lies within 25 degrees of
  /// `normal` (any length; a zero vector: 0).
  [[nodiscard]] double penetration_along(const std::array<double, 3>& normal) const noexcept;
  [[nodiscard]] std::uint32_t count() const noexcept { return count_; }

 private:
  std::array<hcp_contact, kMaxContacts> contacts_{};
  std::uint32_t count_ = 0;
  std::array<bool, kMaxContacts> changed_{};
  std::array<TimePoint, kMaxContacts> sent_{};
  bool clear_due_ = false;
};

}  // namespace hapticctrl::client
