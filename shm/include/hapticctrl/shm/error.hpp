#pragma once
/// @file error.hpp
/// The one exception of the shm layer's setup code (creating, finding and attaching segments).

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "hapticctrl/shm/layout.hpp"

namespace hapticctrl::shm {

/// Why a create or attach failed; every value comes with a message that says what to do.
enum class ShmErrc : std::uint8_t {
  kBadInstanceName,
  kAlreadyRunning,    ///< create: a live core owns the instance
  kNoController,      ///< attach: no segment, or it was left by a dead core
  kAbiMismatch,       ///< attach: segment built by another ABI version
  kLayoutMismatch,    ///< attach: sizes/offsets differ from this program's
  kPermissionDenied,  ///< the OS refused access
  kInsecure,          ///< something another user could have planted or stands in for the core
  kWriterConflict,    ///< another live process already writes that region / no free ctrl slot
  kSystem,            ///< any other OS error (message has errno text)
};

/// Exception for every setup failure of the shm layer: what happened (`code()`), about which
/// region where it is about one (`region()`: a writer conflict names the region claimed), so that
/// a caller decides on them and never on the text, which is for people.
class ShmError : public std::runtime_error {
 public:
  ShmError(ShmErrc code, const std::string& message, std::optional<RegionId> region = std::nullopt)
      : std::runtime_error(message), code_(code), region_(region) {}
  [[nodiscard]] ShmErrc code() const noexcept { return code_; }
  [[nodiscard]] std::optional<RegionId> region() const noexcept { return region_; }

 private:
  ShmErrc code_;
  std::optional<RegionId> region_;
};

/// Throws ShmError for a failed system call: kPermissionDenied (with what to do) for EACCES and
/// EPERM, kSystem with the errno text otherwise.
[[noreturn]] void throw_system_error(const std::string& what, int error);

/// Group id of `group`; the caller's effective group when empty. Throws ShmError(kSystem) for an
/// unknown group.
[[nodiscard]] unsigned group_id(const std::string& group);

}  // namespace hapticctrl::shm
