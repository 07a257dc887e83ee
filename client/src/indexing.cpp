// VirtuoseAPI's indexing, in the client library (see indexing.hpp).
#include "indexing.hpp"

namespace hapticctrl::client {
namespace {

// VirtuoseAPI's modes: 0 all, 1 translations, 2 none, 3 all / 4 translations / 6 rotations
// with forces inhibited while shifted, 7 rotations.
constexpr std::uint32_t kAll = 0;
constexpr std::uint32_t kTranslations = 1;
constexpr std::uint32_t kAllInhibited = 3;
constexpr std::uint32_t kTranslationsInhibited = 4;
constexpr std::uint32_t kNotAMode = 5;
constexpr std::uint32_t kRotationsInhibited = 6;
constexpr std::uint32_t kRotations = 7;

Eigen::Vector3d position_of(const Pose7& p) noexcept {
  return {p[0], p[1], p[2]};
}

/// The pose's quaternion as given: an application's non-unit one stays so through the offset,
/// and the connection refuses it.
Eigen::Quaterniond quaternion_of(const Pose7& p) noexcept {
  return {p[6], p[3], p[4], p[5]};
}

Eigen::Quaterniond rotation_of(const Pose7& p) noexcept {
  return quaternion_of(p).normalized();
}

Pose7 pose_of(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) noexcept {
  return {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
}

Vector6 rotate_angular(const Eigen::Quaterniond& r, const Vector6& v) noexcept {
  const Eigen::Vector3d w = r * Eigen::Vector3d(v[3], v[4], v[5]);
  return {v[0], v[1], v[2], w.x(), w.y(), w.z()};
}

}  // namespace

bool Indexing::set_mode(std::uint32_t mode) noexcept {
  if (mode > kRotations || mode == kNotAMode) {
    return false;
  }
  mode_ = mode;
  return true;
}

bool Indexing::indexes_translation() const noexcept {
  return mode_ == kAll || mode_ == kTranslations || mode_ == kAllInhibited ||
         mode_ == kTranslationsInhibited;
}

bool Indexing::indexes_rotation() const noexcept {
  return mode_ == kAll || mode_ == kAllInhibited || mode_ == kRotationsInhibited ||
         mode_ == kRotations;
}

bool Indexing::forces_inhibited() const noexcept {
  return shifted_ && (mode_ == kAllInhibited || mode_ == kTranslationsInhibited ||
                      mode_ == kRotationsInhibited);
}

void Indexing::press(const Pose7& physical) noexcept {
  if (!shifted_) {
    frozen_ = avatar(physical);
    shifted_ = true;
  }
}

void Indexing::release(const Pose7& physical) noexcept {
  if (shifted_) {
    offset_ = offset_at(physical);
    shifted_ = false;
  }
}

Indexing::Offset Indexing::offset_at(const Pose7& physical) const noexcept {
  Offset o = offset_;
  if (shifted_ && indexes_translation()) {
    o.translation = position_of(frozen_) - position_of(physical);
  }
  if (shifted_ && indexes_rotation()) {
    o.rotation = (rotation_of(frozen_) * rotation_of(physical).conjugate()).normalized();
  }
  return o;
}

Pose7 Indexing::avatar(const Pose7& physical) const noexcept {
  const Offset o = offset_at(physical);
  return pose_of(position_of(physical) + o.translation, o.rotation * rotation_of(physical));
}

Vector6 Indexing::avatar_twist(const Pose7& physical, const Vector6& twist) const noexcept {
  Vector6 v = rotate_angular(offset_at(physical).rotation, twist);
  for (std::size_t i = 0; i < 3 && shifted_ && indexes_translation(); ++i) {
    v[i] = 0.0;  // the avatar keeps still on the indexed axes
  }
  for (std::size_t i = 3; i < 6 && shifted_ && indexes_rotation(); ++i) {
    v[i] = 0.0;
  }
  return v;
}

Vector6 Indexing::to_avatar(const Pose7& physical, const Vector6& wrench) const noexcept {
  return rotate_angular(offset_at(physical).rotation, wrench);
}

Pose7 Indexing::to_physical(const Pose7& physical, const Pose7& object) const noexcept {
  const Offset o = offset_at(physical);
  return pose_of(position_of(object) - o.translation,
                 o.rotation.conjugate() * quaternion_of(object));
}

Vector6 Indexing::to_physical(const Pose7& physical, const Vector6& v) const noexcept {
  return rotate_angular(offset_at(physical).rotation.conjugate(), v);
}

}  // namespace hapticctrl::client
