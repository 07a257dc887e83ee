#pragma once
// Private to hapticctrl-mujoco's World (world.hpp): the engine's model and data it owns, and the
// model's geoms as a view draws them (world_geoms.cpp), shared by world.cpp and world_geoms.cpp.
#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "hapticctrl/mujoco/world.hpp"

namespace hapticctrl::mujoco {

/// Element `index` of a MuJoCo array with `width` numbers per object, as a pointer offset.
inline std::ptrdiff_t at(int width, int index) {
  return static_cast<std::ptrdiff_t>(width) * index;
}

/// Each mesh's bounding box in its geom's frame (centre, half-sizes), for views that draw a mesh
/// as its box.
[[nodiscard]] std::vector<std::array<double, 6>> mesh_boxes_of(const mjModel* m);
/// How many geoms a view draws (fixed by the model).
[[nodiscard]] std::size_t drawn_geoms_of(const mjModel* m);

struct World::Engine {
  mjModel* model = nullptr;
  mjData* data = nullptr;
  int body = -1;
  int qpos = 0;  ///< the free joint's address in qpos (position, then quaternion w x y z)
  int dof = 0;   ///< and in qvel (linear velocity in the world, angular in the body's frame)
  /// The contacts are found on a copy of the model whose body's geoms have the report distance
  /// added to their margin, on a copy of the state: raising the physics model's own margins
  /// (with as much gap, so the solver would skip the far contacts) changed box-box contacts
  /// that touched: the peg, pushed into its hole, turned 90 degrees and jammed (2026-12-05).
  mjModel* report_model = nullptr;
  mjData* report_data = nullptr;
  std::vector<double> margin;  ///< the body's geoms' own margin
  /// The scene's explicit pairs (<contact><pair>) with one of the body's geoms, and each one's
  /// own margin: MuJoCo takes a pair's margin from the pair, not from its geoms.
  std::vector<std::pair<int, double>> pair_margins;
  std::vector<int> grips;  ///< adhesion actuators on the body
  /// Each mesh's bounding box in its geom's frame (centre, half-sizes), found once at load.
  std::vector<std::array<double, 6>> mesh_boxes;
  std::size_t drawn_geoms = 0;  ///< the geoms a view draws, counted once at load

  Engine() = default;
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;
  ~Engine() {
    mj_deleteData(report_data);
    mj_deleteModel(report_model);
    mj_deleteData(data);
    mj_deleteModel(model);
  }
};

}  // namespace hapticctrl::mujoco
