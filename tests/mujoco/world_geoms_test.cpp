// The scene as a view draws it (world_geoms.cpp): every visible geom with its shape, pose and
// colour, a mesh as its bounding box.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "hapticctrl/mujoco/world.hpp"
#include "temp_model.hpp"

namespace hapticctrl::mujoco {
namespace {

using test::TempModel;

TEST(WorldGeoms, EveryVisibleGeomIsListedWithItsShapeAndAMeshAsItsBox) {
  // A mesh spanning x 0..0.2, y 0..0.1, z 0..0.04: MuJoCo keeps its vertices centred on their
  // centroid and along their principal axes (in whichever order), the geom's frame moved and
  // turned to match; the box is where the vertices are.
  const TempModel model(R"(<mujoco><asset><mesh name="wedge" vertex="0 0 0  0.2 0 0  0 0.1 0
      0.2 0.1 0  0 0 0.04  0.2 0 0.04  0 0.1 0.04  0.2 0.1 0.04"/></asset>
    <worldbody>
      <geom name="floor" type="plane" size="0.5 0.4 0.01"/>
      <geom name="hidden" type="sphere" size="0.01" pos="0 0 1" rgba="1 1 1 0"/>
      <geom name="wedge" type="mesh" mesh="wedge" pos="0.3 0 0.1" contype="0" conaffinity="0"/>
      <body name="held" pos="0 0 0.2"><freejoint/>
        <geom type="capsule" size="0.01 0.03" rgba="0 1 0 1"/>
        <geom type="cylinder" size="0.02 0.01" pos="0.05 0 0"/>
        <geom type="ellipsoid" size="0.01 0.02 0.03" pos="-0.05 0 0"/>
      </body></worldbody></mujoco>)");
  World w(model.path(), "held", 0.0);
  EXPECT_EQ(w.visible_geoms(), 5U);
  std::array<GeomView, 8> out{};
  ASSERT_EQ(w.geoms(out), 5U);
  EXPECT_EQ(out[0].type, 0);  // the plane, its half-extents
  EXPECT_DOUBLE_EQ(out[0].size[0], 0.5);
  EXPECT_FALSE(out[0].coupled);
  EXPECT_EQ(out[1].type, 6);  // the mesh, as a box
  std::array<double, 3> half = out[1].size;
  std::sort(half.begin(), half.end());
  EXPECT_NEAR(half[0], 0.02, 1e-6);
  EXPECT_NEAR(half[1], 0.05, 1e-6);
  EXPECT_NEAR(half[2], 0.1, 1e-6);
  EXPECT_NEAR(out[1].pose[0], 0.4, 1e-6);  // x 0.3..0.5
  EXPECT_NEAR(out[1].pose[1], 0.05, 1e-6);
  EXPECT_NEAR(out[1].pose[2], 0.12, 1e-6);
  EXPECT_EQ(out[2].type, 3);
  EXPECT_TRUE(out[2].coupled);
  EXPECT_NEAR(out[2].pose[2], 0.2, 1e-12);
  EXPECT_FLOAT_EQ(out[2].rgba[1], 1.0F);
  EXPECT_EQ(out[3].type, 5);
  EXPECT_NEAR(out[3].pose[0], 0.05, 1e-12);
  EXPECT_EQ(out[4].type, 4);
  EXPECT_DOUBLE_EQ(out[4].size[2], 0.03);
  std::array<GeomView, 2> room{};
  EXPECT_EQ(w.geoms(room), 2U) << "no more than there is room for";
}

}  // namespace
}  // namespace hapticctrl::mujoco
