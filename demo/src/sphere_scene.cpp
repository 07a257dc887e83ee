// Implements sphere_scene.hpp: the demo client's physics engine: two half-rigid spheres, one fixed,
// one mobile (mass, isotropic inertia) coupled to the arm.
#include "hapticctrl/demo/sphere_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hapticctrl::demo {
namespace {

void require_positive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string(name) + " must be a positive finite number");
  }
}

/// Scales `v` down to norm `limit` if it is longer (friction cones, rolling limits).
void clamp_norm(Eigen::Vector3d& v, double limit) noexcept {
  const double norm = v.norm();
  if (norm > limit) {
    v *= limit / norm;
  }
}

}  // namespace

void SceneConfig::validate() const {
  require_positive(fixed_radius, "fixed sphere radius");
  require_positive(mobile_radius, "mobile sphere radius");
  require_positive(mass, "mass");
  require_positive(contact_stiffness, "contact stiffness");
  if (!(contact_damping >= 0.0) || !std::isfinite(contact_damping)) {
    throw std::invalid_argument("contact damping must be finite and >= 0");
  }
  if (!(friction >= 0.0) || !std::isfinite(friction) || !(rolling_resistance >= 0.0) ||
      !std::isfinite(rolling_resistance)) {
    throw std::invalid_argument("friction and rolling resistance must be finite and >= 0");
  }
  if (!fixed_center.allFinite() || !gravity_vector.allFinite() ||
      std::abs(toward.norm() - 1.0) > 1e-9) {
    throw std::invalid_argument("the fixed sphere's centre and gravity must be finite");
  }
}

SphereScene::SphereScene(const SceneConfig& config, const SphereState& start) noexcept
    : config_(config), state_(start), gains_(gains_for(0.0)) {}

SphereScene::ContactGains SphereScene::gains_for(double dt) const noexcept {
  const double m = config_.mass;
  const double inertia = config_.inertia();
  const double r2 = config_.mobile_radius * config_.mobile_radius;
  // Friction acts at the contact point, which both translation and rotation move.
  const double contact_point_mass = m * inertia / (inertia + m * r2);
  // Half of the explicit bound's share for the stiffness (k dt^2 / m <= 0.5, of 4): the client
  // library adds the coupling and its passivity damper on the same motion. At m / dt^2 the
  // rolling patch, the friction and that damper rang at the step's Nyquist rate on a 10 ms step
  // (2026-12-07); below 4 ms no gain of the default scene reaches the bound.
  const auto stiffness = [dt](double k, double mass) {
    return dt > 0.0 ? std::min(k, 0.5 * mass / (dt * dt)) : k;
  };
  const auto damping = [dt](double b, double mass) {
    return dt > 0.0 ? std::min(b, 0.5 * mass / dt) : b;
  };
  ContactGains g;
  g.normal_k = stiffness(config_.contact_stiffness, m);
  g.normal_b = damping(config_.contact_damping, m);
  g.tangent_k = stiffness(config_.contact_stiffness, contact_point_mass);
  g.tangent_b = damping(config_.contact_damping, contact_point_mass);
  g.rolling_k = stiffness(config_.contact_stiffness * r2, inertia);
  g.rolling_b = damping(config_.contact_damping * r2, inertia);
  return g;
}

void SphereScene::move_obstacle(const Eigen::Vector3d& by) noexcept {
  if (by.allFinite()) {
    config_.fixed_center += by;
  }
}

double SphereScene::penetration() const noexcept {
  return std::max(0.0, contact().depth);
}

SphereScene::Contact SphereScene::contact() const noexcept {
  Contact c;
  if (config_.obstacle == Obstacle::kWall) {
    c.normal = -config_.toward;  // the wall faces the side the sphere starts on
    c.depth = config_.mobile_radius - (config_.fixed_center - state_.position).dot(config_.toward);
  } else {
    const Eigen::Vector3d offset = state_.position - config_.fixed_center;
    const double distance = offset.norm();
    if (distance <= 0.0) {
      return c;  // concentric: no direction to push along; treated as apart
    }
    c.normal = offset / distance;
    c.depth = config_.fixed_radius + config_.mobile_radius - distance;
  }
  const Eigen::Vector3d lever = -config_.mobile_radius * c.normal;  // centre -> contact point
  const Eigen::Vector3d velocity = state_.velocity + state_.angular_velocity.cross(lever);
  c.slip_velocity = velocity - velocity.dot(c.normal) * c.normal;
  return c;
}

double SphereScene::normal_push(const Contact& c) const noexcept {
  if (c.depth <= 0.0) {
    return 0.0;
  }
  const double depth_rate = -state_.velocity.dot(c.normal);
  return std::max(0.0, gains_.normal_k * c.depth + gains_.normal_b * depth_rate);
}

Eigen::Vector3d SphereScene::contact_force() const noexcept {
  const Contact c = contact();
  return force_of(c, normal_push(c));
}

Eigen::Vector3d SphereScene::force_of(const Contact& c, double push) const noexcept {
  if (push <= 0.0) {
    return Eigen::Vector3d::Zero();
  }
  Eigen::Vector3d friction = -gains_.tangent_k * stretch_ - gains_.tangent_b * c.slip_velocity;
  clamp_norm(friction, config_.friction * push);
  return push * c.normal + friction;
}

Eigen::Vector3d SphereScene::rolling_torque(double push) const noexcept {
  Eigen::Vector3d torque = -gains_.rolling_k * twist_ - gains_.rolling_b * state_.angular_velocity;
  clamp_norm(torque, config_.rolling_resistance * push * config_.mobile_radius);
  return torque;
}

void SphereScene::update_stretch(const Contact& c, double push, double dt) noexcept {
  if (push <= 0.0) {
    stretch_.setZero();  // apart: the next touch anchors afresh
    twist_.setZero();
    return;
  }
  twist_ += state_.angular_velocity * dt;
  // Beyond the limit the patch rolls on / the anchor slides along.
  clamp_norm(twist_, config_.rolling_resistance * push * config_.mobile_radius / gains_.rolling_k);
  stretch_ += c.slip_velocity * dt;
  stretch_ -= stretch_.dot(c.normal) * c.normal;  // stay in the tangent plane
  clamp_norm(stretch_, config_.friction * push / gains_.tangent_k);
}

void SphereScene::step(const client::Vector6& coupling, const client::Vector6& applied,
                       double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return;
  }
  gains_ = gains_for(dt);
  const Contact touching = contact();
  const double push = normal_push(touching);
  update_stretch(touching, push, dt);
  const Eigen::Vector3d contact_push = force_of(touching, push);
  Eigen::Vector3d force = contact_push;
  // Friction acts at the contact point, so it also turns the sphere; the patch resists that.
  Eigen::Vector3d torque =
      (-config_.mobile_radius * touching.normal).cross(contact_push) + rolling_torque(push);
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    force(i) += coupling[k] + applied[k];
    torque(i) += coupling[k + 3] + applied[k + 3];
  }
  if (!force.allFinite() || !torque.allFinite()) {
    return;  // a corrupt input must not poison the scene
  }
  if (config_.gravity) {
    force += config_.mass * config_.gravity_vector;
  }
  // Semi-implicit Euler: velocities first, then positions from the new velocities. An isotropic
  // inertia has no gyroscopic term.
  state_.velocity += force / config_.mass * dt;
  state_.position += state_.velocity * dt;
  state_.angular_velocity += torque / config_.inertia() * dt;
  const Eigen::Vector3d rotation = state_.angular_velocity * dt;
  const double angle = rotation.norm();
  if (angle > 0.0) {
    state_.orientation =
        (Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation / angle)) * state_.orientation)
            .normalized();
  }
}

std::optional<client::Contact> SphereScene::contact_report(double near,
                                                           double max_stiffness) const noexcept {
  const Contact c = contact();
  if (c.depth < -near) {
    return std::nullopt;
  }
  const Eigen::Vector3d point = state_.position - config_.mobile_radius * c.normal;
  client::Contact out;
  out.point = {point.x(), point.y(), point.z()};
  out.normal = {c.normal.x(), c.normal.y(), c.normal.z()};
  out.distance = -c.depth;
  out.stiffness = max_stiffness > 0.0 ? std::min(config_.contact_stiffness, max_stiffness)
                                      : config_.contact_stiffness;
  out.damping = config_.contact_damping;
  out.friction_static = config_.friction;
  out.friction_dynamic = config_.friction;
  return out;
}

std::optional<client::Contact> SphereScene::contact_report_toward(
    const Eigen::Vector3d& probe, double near, double max_stiffness) const noexcept {
  // Mark et al. 1996: the local plane is the surface's tangent plane nearest the haptic probe.
  // Tangent at the mobile sphere instead, behind a 10 ms cycle (a soft coupling) the plane
  // turned under the handle as the sphere rolled off the fixed one, and the handle slid off with
  // it (2026-12-04).
  const Eigen::Vector3d toward = probe - config_.fixed_center;
  if (config_.obstacle == Obstacle::kWall || toward.norm() <= 0.0) {
    return contact_report(near, max_stiffness);
  }
  const Eigen::Vector3d n = toward.normalized();
  const double gap = (state_.position - config_.fixed_center).dot(n) - config_.fixed_radius -
                     config_.mobile_radius;
  if (gap > near) {
    return std::nullopt;
  }
  // The surface's gains as contact_report gives them; its plane, the one toward the probe.
  std::optional<client::Contact> out =
      contact_report(std::numeric_limits<double>::infinity(), max_stiffness);
  const Eigen::Vector3d point = state_.position - config_.mobile_radius * n;
  out->point = {point.x(), point.y(), point.z()};
  out->normal = {n.x(), n.y(), n.z()};
  out->distance = gap;
  return out;
}

std::optional<client::Contact> SphereScene::surface_for_center(
    double near, double max_stiffness) const noexcept {
  std::optional<client::Contact> out = contact_report(near, max_stiffness);
  if (out) {
    const Contact c = contact();
    const Eigen::Vector3d point = state_.position + c.depth * c.normal;
    out->point = {point.x(), point.y(), point.z()};
  }
  return out;
}

void SphereScene::follow(const client::Pose7& pose, const client::Vector6& twist) noexcept {
  state_.position = {pose[0], pose[1], pose[2]};
  state_.orientation = Eigen::Quaterniond(pose[6], pose[3], pose[4], pose[5]).normalized();
  state_.velocity = {twist[0], twist[1], twist[2]};
  state_.angular_velocity = {twist[3], twist[4], twist[5]};
}

client::Pose7 SphereScene::pose() const noexcept {
  const Eigen::Quaterniond& q = state_.orientation;
  return {
      state_.position.x(), state_.position.y(), state_.position.z(), q.x(), q.y(), q.z(), q.w()};
}

client::Vector6 SphereScene::twist() const noexcept {
  return {state_.velocity.x(),         state_.velocity.y(),         state_.velocity.z(),
          state_.angular_velocity.x(), state_.angular_velocity.y(), state_.angular_velocity.z()};
}

double SphereScene::kinetic_energy() const noexcept {
  return 0.5 * config_.mass * state_.velocity.squaredNorm() +
         0.5 * config_.inertia() * state_.angular_velocity.squaredNorm();
}

}  // namespace hapticctrl::demo
