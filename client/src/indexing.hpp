#pragma once
/// @file indexing.hpp
/// VirtuoseAPI's indexing, done in the client library: while the shift is pressed the avatar (the
/// pose the application sees) keeps still on the indexed axes and the handle moves freely;
/// releasing keeps the new offset between them. The translation is indexed by an offset added
/// to the handle's position, the orientation by a rotation applied to the handle's (about its
/// own point), so linear quantities never rotate and angular ones turn with the offset.
/// Private to the client library. Real-time contract: every member is noexcept and allocates
/// nothing (a value type; the caller serialises access).
#include <Eigen/Geometry>
#include <cstdint>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::client {

class Indexing {
 public:
  /// A VirtuoseAPI indexing mode (0-4, 6, 7); other values leave the mode as it was and return
  /// false.
  bool set_mode(std::uint32_t mode) noexcept;
  [[nodiscard]] std::uint32_t mode() const noexcept { return mode_; }

  /// Presses the shift with the handle at `physical` (a second press is ignored).
  void press(const Pose7& physical) noexcept;
  /// Releases it with the handle at `physical`: the offset reached is kept.
  void release(const Pose7& physical) noexcept;
  [[nodiscard]] bool shifted() const noexcept { return shifted_; }
  /// Shifted in a mode that inhibits forces meanwhile.
  [[nodiscard]] bool forces_inhibited() const noexcept;

  /// The avatar of the handle at `physical`.
  [[nodiscard]] Pose7 avatar(const Pose7& physical) const noexcept;
  /// The avatar's twist, the handle at `physical` moving with `twist` (frozen axes: zero).
  [[nodiscard]] Vector6 avatar_twist(const Pose7& physical, const Vector6& twist) const noexcept;
  /// A wrench on the handle's side (the controller's) as the avatar's side sees it.
  [[nodiscard]] Vector6 to_avatar(const Pose7& physical, const Vector6& wrench) const noexcept;
  /// An object pose given in the avatar's frame, in the handle's (what the controller couples).
  [[nodiscard]] Pose7 to_physical(const Pose7& physical, const Pose7& object) const noexcept;
  /// An object twist or a wrench given on the avatar's side, on the handle's.
  [[nodiscard]] Vector6 to_physical(const Pose7& physical, const Vector6& v) const noexcept;

 private:
  struct Offset {
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  };
  [[nodiscard]] bool indexes_translation() const noexcept;
  [[nodiscard]] bool indexes_rotation() const noexcept;
  /// The offset in force with the handle at `physical` (while shifted it follows the handle).
  [[nodiscard]] Offset offset_at(const Pose7& physical) const noexcept;

  std::uint32_t mode_ = 0;  // INDEXING_ALL
  bool shifted_ = false;
  Offset offset_;
  Pose7 frozen_{0, 0, 0, 0, 0, 0, 1};  // the avatar when the shift was pressed
};

}  // namespace hapticctrl::client
