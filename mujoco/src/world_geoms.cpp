// Implements world.hpp's view of the scene: the geoms a view draws (planes, boxes, spheres,
// capsules, ellipsoids, cylinders; meshes as their bounding boxes), with their poses and colours.
#include <algorithm>
#include <cmath>

#include "world_engine.hpp"

namespace hapticctrl::mujoco {
namespace {

/// Geom `g`'s colour: its material's when it has one (MuJoCo draws that), else its own.
const float* rgba_of(const mjModel* m, int g) {
  const int material = m->geom_matid[g];
  return material >= 0 ? m->mat_rgba + at(4, material) : m->geom_rgba + at(4, g);
}

/// Whether a view draws geom `g`: visible, and a shape world_t carries.
bool drawn(const mjModel* m, int g) {
  const int type = m->geom_type[g];
  return rgba_of(m, g)[3] > 0.0F && type != mjGEOM_HFIELD && type <= mjGEOM_MESH;
}

}  // namespace

/// Each mesh's bounding box, in the frame MuJoCo keeps its vertices in (its geoms').
std::vector<std::array<double, 6>> mesh_boxes_of(const mjModel* m) {
  std::vector<std::array<double, 6>> boxes;
  for (int mesh = 0; mesh < m->nmesh; ++mesh) {
    std::array<double, 3> low{HUGE_VAL, HUGE_VAL, HUGE_VAL};
    std::array<double, 3> high{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      const float* p = m->mesh_vert + at(3, m->mesh_vertadr[mesh] + v);
      for (std::size_t k = 0; k < 3; ++k) {
        low[k] = std::min(low[k], static_cast<double>(p[k]));
        high[k] = std::max(high[k], static_cast<double>(p[k]));
      }
    }
    std::array<double, 6> box{};
    for (std::size_t k = 0; k < 3 && m->mesh_vertnum[mesh] > 0; ++k) {
      box[k] = 0.5 * (low[k] + high[k]);
      box[3 + k] = 0.5 * (high[k] - low[k]);
    }
    boxes.push_back(box);
  }
  return boxes;
}

/// How many geoms a view draws (fixed by the model).
std::size_t drawn_geoms_of(const mjModel* m) {
  std::size_t n = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    n += drawn(m, g) ? 1U : 0U;
  }
  return n;
}

std::size_t World::visible_geoms() const noexcept {
  return engine_->drawn_geoms;
}

std::size_t World::geoms(std::span<GeomView> out) const noexcept {
  const Engine& e = *engine_;
  const mjModel* m = e.model;
  std::size_t n = 0;
  for (int g = 0; g < m->ngeom && n < out.size(); ++g) {
    if (!drawn(m, g)) {
      continue;
    }
    GeomView& v = out[n++];
    v.type = m->geom_type[g];
    const mjtNum* size = m->geom_size + at(3, g);
    std::copy(size, size + 3, v.size.begin());
    const mjtNum* rotation = e.data->geom_xmat + at(9, g);
    mjtNum position[3];
    mju_copy3(position, e.data->geom_xpos + at(3, g));
    if (v.type == mjGEOM_MESH && m->geom_dataid[g] >= 0) {
      const std::array<double, 6>& box = e.mesh_boxes[static_cast<std::size_t>(m->geom_dataid[g])];
      mjtNum centre[3];
      mju_rotVecMat(centre, box.data(), rotation);
      mju_addTo3(position, centre);
      std::copy(box.begin() + 3, box.end(), v.size.begin());
      v.type = mjGEOM_BOX;
    }
    mjtNum quat[4];  // w x y z
    mju_mat2Quat(quat, rotation);
    v.pose = {position[0], position[1], position[2], quat[1], quat[2], quat[3], quat[0]};
    const float* rgba = rgba_of(m, g);
    std::copy(rgba, rgba + 4, v.rgba.begin());
    v.coupled = m->geom_bodyid[g] == e.body;
  }
  return n;
}

}  // namespace hapticctrl::mujoco
