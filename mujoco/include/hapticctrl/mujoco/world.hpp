#pragma once
/// @file world.hpp
/// A MuJoCo model and its data, with the one free body the operator holds through the arm.
/// Setup (load) throws; the step and the getters do not allocate (MuJoCo's data is allocated at
/// load) and never throw: they run in hapticctrl-mujoco's stepping loop.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "hapticctrl/client/types.hpp"
#include "hapticctrl/mujoco/contact_mapping.hpp"

namespace hapticctrl::mujoco {

/// One geom as a view draws it (world_t's world_geom_t): MuJoCo's type and half-sizes, a mesh as
/// its bounding box (type box, posed at the box's centre).
struct GeomView {
  int type = 0;  ///< mjtGeom: 0 plane, 2 sphere, 3 capsule, 4 ellipsoid, 5 cylinder, 6 box
  std::array<double, 3> size{};
  client::Pose7 pose{0, 0, 0, 0, 0, 0, 1};  ///< in the world
  std::array<float, 4> rgba{};
  bool coupled = false;  ///< part of the body the hand holds
};

class World {
 public:
  /// Loads an MJCF file and finds the coupled body: `body`, or (empty) the model's custom text
  /// "hapticctrl_body". Throws std::invalid_argument with MuJoCo's own error text for a bad file,
  /// and a clear message for a body that is missing or not free (a free joint, its only joint).
  /// `timestep` > 0 overrides the model's.
  World(const std::string& path, const std::string& body, double timestep);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  [[nodiscard]] double timestep() const noexcept;
  [[nodiscard]] double time() const noexcept;
  [[nodiscard]] const std::string& body_name() const noexcept { return body_name_; }
  [[nodiscard]] double mass() const noexcept;
  /// Principal moments of inertia about the body's centre of mass [kg.m^2].
  [[nodiscard]] std::array<double, 3> inertia() const noexcept;

  /// One engine step with `wrench` (force, torque; world frame) applied at the body's origin,
  /// the point whose pose is sent. A non-finite wrench is applied as zero. Cycle-safe.
  void step(const client::Vector6& wrench) noexcept;
  /// The body's origin and orientation in the world (from the state after the last step).
  [[nodiscard]] client::Pose7 pose() const noexcept;
  /// Its origin's velocity and its angular velocity, world frame.
  [[nodiscard]] client::Vector6 twist() const noexcept;
  /// Contacts are found this far apart (m) and reported; the physics is not changed (they are
  /// found on a copy of the model and the state). Clamped to 0..1 m. Cycle-safe.
  void set_report_distance(double distance) noexcept;
  /// The body's contacts and near contacts in the state after the last step, deepest first, at
  /// most out.size(): the count. Runs MuJoCo's collision pass on the copy (a few microseconds
  /// for the shipped scenes); allocates nothing. Cycle-safe.
  std::size_t contacts(std::span<EngineContact> out) noexcept;
  /// Total force the contacts put on the body in the last step (world frame, N).
  [[nodiscard]] std::array<double, 3> contact_force() const noexcept;
  /// Steps MuJoCo found unstable and reset (its bad-acceleration warning).
  [[nodiscard]] int instabilities() const noexcept;
  /// The model's initial state again (the 'r' key).
  void reset() noexcept;

  /// Whether the model gives the coupled body a grip: an adhesion actuator on it (MJCF
  /// <adhesion body="..."/>), which the 'g' key switches.
  [[nodiscard]] bool has_grip() const noexcept;
  /// The grip fully on (its control range's top) or off. Cycle-safe.
  void set_grip(bool on) noexcept;

  /// The model's visible geoms (alpha above 0; height fields and signed distance fields are
  /// left out) in the state after the last step, at most out.size(): the count written.
  /// Allocates nothing. Cycle-safe.
  std::size_t geoms(std::span<GeomView> out) const noexcept;
  /// How many geoms geoms() would write given room for all.
  [[nodiscard]] std::size_t visible_geoms() const noexcept;

  /// Where the scene's other free bodies are (name, position in the world; unnamed ones as
  /// "body N"), for the summary. Allocates: not for the stepping loop.
  [[nodiscard]] std::vector<std::pair<std::string, std::array<double, 3>>> free_bodies() const;
  /// The scene's named hinge and slide joints and their positions (rad, m), for the summary.
  /// Allocates: not for the stepping loop.
  [[nodiscard]] std::vector<std::pair<std::string, double>> joints() const;

 private:
  struct Engine;
  std::unique_ptr<Engine> engine_;
  std::string body_name_;
};

/// The MuJoCo library's version, for the start line.
[[nodiscard]] std::string engine_version();

}  // namespace hapticctrl::mujoco
