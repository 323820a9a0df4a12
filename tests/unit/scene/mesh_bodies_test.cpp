// Mesh bodies from scene to world: the physics sees what it sees for a box (mass, principal
// moments, hull vertices), users see the model's own frame (position = centre of mass,
// orientation = the file's axes), and a cube mesh moves exactly like the box shape.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tumble/scene.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

const std::string kMeshDir = std::string(TUMBLE_SOURCE_DIR) + "/assets/meshes/";

std::string drop_scene(const std::string& body) {
  return "[floor]\n[[body]]\nname = \"b\"\n" + body +
         "mass = 1.0\nposition = [0.0, 3.0, 0.0]\n"
         "orientation = { axis = [1.0, 0.0, 1.0], degrees = 30.0 }\n"
         "angular_velocity = [0.0, 0.0, 2.0]\n";
}

TEST(MeshBodies, CubeMeshMovesExactlyLikeTheBoxShape) {
  // The same mass, the same principal moments (m/6), the same 8 corners, identity axes: every
  // operation is the same, so the trajectories agree bit for bit, in every format.
  const Scene box =
      parse_scene(drop_scene("shape = \"box\"\nsize = [1.0, 1.0, 1.0]\n"), "box.toml");
  World box_world(make_world_def(box));
  for (const char* file : {"cube.obj", "cube.stl", "cube.gltf"}) {
    const Scene mesh =
        parse_scene(drop_scene("shape = \"mesh\"\nmesh = \"" + kMeshDir + file + "\"\n"), "m.toml");
    World mesh_world(make_world_def(mesh));
    World reference = box_world;
    for (int i = 0; i < 4000; ++i) {
      reference.step();
      mesh_world.step();
      ASSERT_EQ(mesh_world.bodies()[0].state.x, reference.bodies()[0].state.x)
          << file << " step " << i;
      ASSERT_EQ(mesh_world.bodies()[0].model_orientation().coeffs(),
                reference.bodies()[0].state.q.coeffs())
          << file;
    }
    EXPECT_TRUE(mesh_world.bodies()[0].at_rest) << file;
  }
}

TEST(MeshBodies, LShapeKeepsItsFileFrameAndItsCentreOfMass) {
  // The L-shaped block (unit square minus a quarter, 0.5 thick) has its centre of mass at
  // (5/12, 5/12, 1/4) in its file: off its bounding-box centre (1/2, 1/2, 1/4). Its principal
  // axes are not the file's (the L is symmetric about the x = y plane), yet the scene's
  // orientation and the reported one are the file's frame, and position is the centre of mass.
  const Scene scene = parse_scene("[[body]]\nshape = \"mesh\"\nmesh = \"" + kMeshDir +
                                      "lshape.obj\"\ndensity = 1000.0\nposition = [1.0, 2.0, 3.0]\n"
                                      "orientation = { axis = [0.0, 1.0, 0.0], degrees = 90.0 }\n",
                                  "l.toml");
  const SceneModels models = load_models(scene);
  const WorldDef def = make_world_def(scene, models);
  const World world(def);
  const RigidBody& b = world.bodies()[0];
  EXPECT_NEAR(b.mass(), 375.0, 1e-9);  // 0.375 m³ at 1000 kg/m³
  EXPECT_NEAR((b.com_offset() - Vec3(5.0 / 12.0, 5.0 / 12.0, 0.25)).norm(), 0.0, 1e-12);
  EXPECT_EQ(b.state.x, Vec3(1.0, 2.0, 3.0));
  const Quat given(Eigen::AngleAxisd(kPi / 2.0, Vec3::UnitY()));
  EXPECT_NEAR(b.model_orientation().angularDistance(given), 0.0, 1e-12);
  // Not the identity: the L's principal axes lie along and across its diagonal.
  EXPECT_GT(b.principal_axes().angularDistance(Quat::Identity()), 0.1);
  // Hull vertices in the body frame, about the centre of mass: a model corner maps back to the
  // file's coordinates through the model pose.
  const Mat3 R_model = b.model_orientation().toRotationMatrix();
  bool found_origin = false;
  for (const Vec3& v : b.vertices()) {
    const Vec3 world_point = b.state.x + b.state.R * v;
    const Vec3 file_point = R_model.transpose() * (world_point - b.state.x) + b.com_offset();
    if (file_point.norm() < 1e-12) found_origin = true;
  }
  EXPECT_TRUE(found_origin) << "the file's corner (0, 0, 0) is a contact vertex";
  // The L's hull: its 12 corners but the two of the inner (re-entrant) edge.
  EXPECT_EQ(b.vertices().size(), 10u);
}

TEST(MeshBodies, BadMeshIsAnErrorNamingTheFile) {
  const Scene scene = parse_scene(
      "[[body]]\nshape = \"mesh\"\nmesh = \"no/such/model.obj\"\nmass = 1\n", "dir/s.toml");
  try {
    (void)make_world_def(scene);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_NE(e.describe().find("dir/no/such/model.obj"), std::string::npos) << e.describe();
  }
}

TEST(MeshBodies, SceneWithoutMeshesLoadsNothing) {
  const Scene scene =
      parse_scene(drop_scene("shape = \"box\"\nsize = [1.0, 1.0, 1.0]\n"), "b.toml");
  const SceneModels models = load_models(scene);
  EXPECT_EQ(models.model(0), nullptr);
}

}  // namespace
}  // namespace tumble
