// Scene keys of bodies that meet each other: sphere and radius, fixed, per-body friction,
// [[pair]], [simulation] collisions, and the errors of each (SPEC "Bodies that meet each other").
#include <gtest/gtest.h>

#include <string>

#include "tumble/scene.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

// Parses `text` and checks it fails as bad input at line:column with `needle` in the message.
testing::AssertionResult FailsAt(const std::string& text, int line, int column,
                                 std::string_view needle) {
  try {
    make_world_def(parse_scene(text, "test.toml"));
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::BadInput)
      return testing::AssertionFailure() << "not BadInput: " << e.describe();
    if (e.where().line != line || e.where().column != column)
      return testing::AssertionFailure()
             << "expected " << line << ":" << column << ", got " << e.describe();
    if (std::string_view(e.what()).find(needle) == std::string_view::npos)
      return testing::AssertionFailure() << "message lacks \"" << needle << "\": " << e.describe();
    return testing::AssertionSuccess();
  }
  return testing::AssertionFailure() << "parsed without error";
}

const std::string kBall = R"([[body]]
name = "ball"
shape = "sphere"
radius = 0.1
mass = 0.17
position = [0.0, 1.0, 0.0]
)";

TEST(ContactScene, SphereFixedFrictionAndPairsReachTheWorld) {
  const Scene scene = parse_scene(kBall + R"(friction = 0.4
[[body]]
name = "ramp"
shape = "box"
size = [4.0, 0.2, 1.0]
fixed = true
[[pair]]
bodies = ["ramp", "ball"]
restitution = 0.2
[simulation]
collisions = "floor"
)",
                                  "test.toml");
  ASSERT_EQ(scene.bodies.size(), 2u);
  EXPECT_EQ(scene.bodies[0].shape, Shape::Sphere);
  EXPECT_DOUBLE_EQ(scene.bodies[0].radius_m, 0.1);
  EXPECT_EQ(scene.bodies[0].size, Vec3::Constant(0.2));  // drawn: its diameter
  EXPECT_TRUE(scene.bodies[1].fixed);
  ASSERT_EQ(scene.pairs.size(), 1u);
  EXPECT_EQ(scene.pairs[0].a, 0);  // sorted: (ball, ramp)
  EXPECT_EQ(scene.pairs[0].b, 1);
  EXPECT_FALSE(scene.simulation.collisions);
  const WorldDef def = make_world_def(scene);
  EXPECT_EQ(def.bodies[0].shape, ShapeKind::Sphere);
  // I = 2/5 m r² about every axis.
  EXPECT_NEAR(def.bodies[0].inertia_body.x(), 0.4 * 0.17 * 0.01, 1e-15);
  EXPECT_EQ(def.bodies[0].friction, 0.4);
  EXPECT_TRUE(def.bodies[1].fixed);
  EXPECT_FALSE(def.collisions);
  ASSERT_EQ(def.pairs.size(), 1u);
  EXPECT_EQ(def.pairs[0].restitution, 0.2);
}

TEST(ContactScene, KeysAShapeDoesNotTakeAreErrors) {
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
radius = 0.5
mass = 1.0
)",
                      4, 10, "radius in [[body]] applies only to shape = \"sphere\""));
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "sphere"
mass = 1.0
)",
                      1, 1, "missing key \"radius\""));
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
fixed = true
mass = 2.0
)",
                      5, 8, "mass in [[body]] does not apply to a fixed body"));
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
fixed = true
velocity = [1.0, 0.0, 0.0]
)",
                      5, 12, "velocity in [[body]] does not apply to a fixed body"));
}

TEST(ContactScene, BadPairsAreErrors) {
  EXPECT_TRUE(FailsAt(kBall + R"([[pair]]
bodies = ["ball", "bal"]
)",
                      8, 19, "names no body: \"bal\""));
  EXPECT_TRUE(FailsAt(kBall + R"([[pair]]
bodies = ["ball", "ball"]
)",
                      8, 10, "twice"));
  EXPECT_TRUE(FailsAt(kBall + R"([[pair]]
bodies = ["ball", "floor"]
[[pair]]
bodies = ["floor", "ball"]
)",
                      10, 10, "already given a [[pair]] on line 7"));
}

TEST(ContactScene, OverlappingBodiesAtTheStartAreAnError) {
  // Two unit boxes 0.5 m apart centre to centre: they overlap by 0.5 m, named at the second.
  EXPECT_TRUE(FailsAt(R"([[body]]
name = "a"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
[[body]]
name = "b"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.5, 0.0, 0.0]
)",
                      6, 1, "bodies \"a\" and \"b\" overlap by 0.5 m at t = 0"));
  // Fixed bodies may overlap each other (a table's legs in its top), and pass-through pairs.
  EXPECT_NO_THROW(make_world_def(parse_scene(R"([[body]]
name = "a"
shape = "box"
size = [1.0, 1.0, 1.0]
fixed = true
[[body]]
name = "b"
shape = "box"
size = [1.0, 1.0, 1.0]
fixed = true
position = [0.5, 0.0, 0.0]
)",
                                             "test.toml")));
}

}  // namespace
}  // namespace tumble
