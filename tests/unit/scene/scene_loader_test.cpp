#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "tumble/scene.hpp"

namespace tumble {
namespace {

// A valid body to append after the text under test, so the line numbers of that text are
// unchanged and the scene fails only for what the test means.
constexpr std::string_view kBox = R"(
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
)";

std::string with_box(std::string_view text) {
  return std::string(text) + std::string(kBox);
}

// Parses `text` as "test.toml" and checks that it fails as bad input (exit code 2) at
// line:column with a message containing `needle`.
testing::AssertionResult FailsAt(std::string_view text, int line, int column,
                                 std::string_view needle) {
  try {
    parse_scene(text, "test.toml");
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::BadInput || e.exit_code() != 2)
      return testing::AssertionFailure() << "not BadInput: " << e.describe();
    if (e.where().file != "test.toml" || e.where().line != line || e.where().column != column)
      return testing::AssertionFailure()
             << "expected test.toml:" << line << ":" << column << ", got " << e.describe();
    if (std::string_view(e.what()).find(needle) == std::string_view::npos)
      return testing::AssertionFailure() << "message lacks \"" << needle << "\": " << e.describe();
    return testing::AssertionSuccess();
  }
  return testing::AssertionFailure() << "parsed without error";
}

// ---------------------------------------------------------------------------------------------
// What a valid scene becomes

TEST(SceneLoader, AppliesDefaultsWhenTablesAreOmitted) {
  const Scene scene = parse_scene(R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
)",
                                  "test.toml");
  const SimulationSettings sim;
  EXPECT_EQ(scene.simulation.duration_s, 4.0);
  EXPECT_EQ(scene.simulation.dt_s, 0.001);
  EXPECT_EQ(scene.simulation.integrator, Integrator::Rk4);
  EXPECT_EQ(scene.simulation.rotation, RotationRep::Quaternion);
  EXPECT_EQ(scene.simulation.gravity, Vec3(0.0, -9.81, 0.0));
  EXPECT_EQ(scene.simulation.linear_drag, 0.0);
  EXPECT_EQ(scene.simulation.angular_drag, 0.0);
  EXPECT_FALSE(scene.floor.has_value());
  EXPECT_EQ(scene.render.fps, 60);
  EXPECT_EQ(scene.render.width, 1280);
  EXPECT_EQ(scene.render.height, 720);
  EXPECT_EQ(scene.render.msaa, 4);
  EXPECT_EQ(scene.render.background, (Color{0xdf, 0xe6, 0xee}));
  EXPECT_EQ(scene.camera.position, Vec3(5.0, 3.0, 6.0));
  EXPECT_EQ(scene.camera.target, Vec3(0.0, 0.5, 0.0));
  EXPECT_EQ(scene.camera.up, Vec3(0.0, 1.0, 0.0));
  EXPECT_EQ(scene.camera.fov_deg, 45.0);
  EXPECT_FALSE(scene.camera.follow.has_value());
  EXPECT_EQ(scene.light.direction, Vec3(-0.4, -1.0, -0.3));
  EXPECT_TRUE(scene.light.shadows);

  ASSERT_EQ(scene.bodies.size(), 1u);
  const BodySpec& b = scene.bodies[0];
  EXPECT_EQ(b.name, "body1");
  EXPECT_EQ(b.shape, Shape::Box);
  EXPECT_EQ(b.scale, Vec3::Ones());
  EXPECT_EQ(b.mass, 1.0);
  EXPECT_FALSE(b.density.has_value());
  EXPECT_EQ(b.position, Vec3::Zero());
  EXPECT_EQ(b.orientation.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(b.velocity, Vec3::Zero());
  EXPECT_EQ(b.angular_velocity, Vec3::Zero());
  EXPECT_FALSE(b.restitution.has_value());  // the floor's applies
  EXPECT_EQ(b.color, (Color{0xd9, 0x57, 0x2b}));
  EXPECT_EQ(b.where.file, "test.toml");
  EXPECT_EQ(b.where.line, 1);
}

TEST(SceneLoader, NoFloorTableMeansNoFloor) {
  EXPECT_FALSE(parse_scene(with_box(""), "test.toml").floor.has_value());
}

TEST(SceneLoader, EmptyFloorTableGivesTheDefaultFloor) {
  const Scene scene = parse_scene(with_box("[floor]\n"), "test.toml");
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->height, 0.0);
  EXPECT_EQ(scene.floor->restitution, 0.5);
  EXPECT_EQ(scene.floor->friction, 0.0);
}

TEST(SceneLoader, ReadsEveryKey) {
  const Scene scene = parse_scene(R"(
[simulation]
duration = 2.5
dt = 0.01
integrator = "symplectic-euler"
rotation = "matrix"
gravity = [0.0, -1.62, 0.0]
linear_drag = 0.1
angular_drag = 0.2

[floor]
height = -1.0
restitution = 0.25
friction = 0.3

[render]
fps = 24
width = 640
height = 480
msaa = 0
background = "#000000"

[camera]
position = [1.0, 2.0, 3.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
fov_deg = 60.0
follow = "crate"

[light]
direction = [0.0, -1.0, 0.0]
shadows = false

[[body]]
name = "crate"
shape = "box"
size = [0.5, 1.0, 2.0]
density = 700.0
position = [1.0, 2.0, 3.0]
orientation = { axis = [0.0, 0.0, 1.0], degrees = 180.0 }
velocity = [4.0, 5.0, 6.0]
angular_velocity = [0.1, 0.2, 0.3]
restitution = 0.9
color = "#AbCdEf"

[[body]]
name = "dot"
shape = "particle"
mass = 0.5
size = [0.2, 0.2, 0.2]
)",
                                  "scenes/every_key.toml");
  EXPECT_EQ(scene.simulation.duration_s, 2.5);
  EXPECT_EQ(scene.simulation.dt_s, 0.01);
  EXPECT_EQ(scene.simulation.integrator, Integrator::SymplecticEuler);
  EXPECT_EQ(scene.simulation.rotation, RotationRep::Matrix);
  EXPECT_EQ(scene.simulation.gravity, Vec3(0.0, -1.62, 0.0));
  EXPECT_EQ(scene.simulation.linear_drag, 0.1);
  EXPECT_EQ(scene.simulation.angular_drag, 0.2);
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->height, -1.0);
  EXPECT_EQ(scene.floor->restitution, 0.25);
  EXPECT_EQ(scene.floor->friction, 0.3);
  EXPECT_EQ(scene.render.fps, 24);
  EXPECT_EQ(scene.render.width, 640);
  EXPECT_EQ(scene.render.height, 480);
  EXPECT_EQ(scene.render.msaa, 0);
  EXPECT_EQ(scene.render.background, (Color{0, 0, 0}));
  EXPECT_EQ(scene.camera.position, Vec3(1.0, 2.0, 3.0));
  EXPECT_EQ(scene.camera.target, Vec3(0.0, 0.0, 0.0));
  EXPECT_EQ(scene.camera.up, Vec3(0.0, 0.0, 1.0));
  EXPECT_EQ(scene.camera.fov_deg, 60.0);
  EXPECT_EQ(scene.camera.follow, "crate");
  EXPECT_EQ(scene.light.direction, Vec3(0.0, -1.0, 0.0));
  EXPECT_FALSE(scene.light.shadows);

  ASSERT_EQ(scene.bodies.size(), 2u);
  const BodySpec& crate = scene.bodies[0];
  EXPECT_EQ(crate.name, "crate");
  EXPECT_EQ(crate.shape, Shape::Box);
  EXPECT_EQ(crate.size, Vec3(0.5, 1.0, 2.0));
  EXPECT_FALSE(crate.mass.has_value());
  EXPECT_EQ(crate.density, 700.0);
  EXPECT_EQ(crate.position, Vec3(1.0, 2.0, 3.0));
  // 180 degrees about z maps x to -x; cos/sin of pi in double leave ~1e-16 residue.
  EXPECT_TRUE((crate.orientation * Vec3::UnitX()).isApprox(-Vec3::UnitX(), 1e-12));
  EXPECT_EQ(crate.velocity, Vec3(4.0, 5.0, 6.0));
  EXPECT_EQ(crate.angular_velocity, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(crate.restitution, 0.9);
  EXPECT_EQ(crate.color, (Color{0xab, 0xcd, 0xef}));
  EXPECT_EQ(crate.where.line, 34);
  EXPECT_EQ(crate.where.column, 1);

  const BodySpec& dot = scene.bodies[1];
  EXPECT_EQ(dot.shape, Shape::Particle);
  EXPECT_EQ(dot.mass, 0.5);
  EXPECT_EQ(dot.size, Vec3(0.2, 0.2, 0.2));
  EXPECT_EQ(dot.color, (Color{0x2b, 0x7b, 0xd9}));  // second colour of the palette
}

TEST(SceneLoader, RecordsSourceTextAndStem) {
  const std::string text = with_box("# a comment\n");
  const Scene scene = parse_scene(text, "a/b/drop.toml");
  EXPECT_EQ(scene.source_name, "a/b/drop.toml");
  EXPECT_EQ(scene.source_text, text);
  EXPECT_EQ(scene.stem, "drop");
}

TEST(SceneLoader, AcceptsAnIntegerWhereARealIsExpected) {
  const Scene scene =
      parse_scene(with_box("[simulation]\nduration = 3\ngravity = [0, -10, 0]\n"), "test.toml");
  EXPECT_EQ(scene.simulation.duration_s, 3.0);
  EXPECT_EQ(scene.simulation.gravity, Vec3(0.0, -10.0, 0.0));
}

TEST(SceneLoader, ConvertsDegreesToAQuaternion) {
  const Scene scene = parse_scene(R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
orientation = { axis = [0, 1, 0], degrees = 90 }
)",
                                  "test.toml");
  const Quat& q = scene.bodies[0].orientation;
  // A right-handed quarter turn about y takes x to -z; 1e-12 covers cos(pi/2) ~ 6e-17 residue.
  EXPECT_NEAR((q * Vec3::UnitX() - Vec3(0.0, 0.0, -1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
}

TEST(SceneLoader, NormalisesTheOrientationAxis) {
  const auto orientation_for = [](std::string_view axis) {
    const std::string text = R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
orientation = { axis = )" + std::string(axis) +
                             ", degrees = 30 }\n";
    return parse_scene(text, "test.toml").bodies[0].orientation;
  };
  const Quat unit = orientation_for("[1, 0, 1]");
  const Quat scaled = orientation_for("[1e3, 0, 1e3]");
  // The same rotation, and a unit quaternion, whatever the axis length (to round-off).
  EXPECT_NEAR(unit.angularDistance(scaled), 0.0, 1e-12);
  EXPECT_NEAR(scaled.norm(), 1.0, 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(unit).angle(), radians(30.0), 1e-12);
}

TEST(SceneLoader, DefaultNamesAndColoursFollowBodyOrder) {
  std::string text;
  for (int i = 0; i < 7; ++i) text += "[[body]]\nshape = \"particle\"\nmass = 1\n";
  const Scene scene = parse_scene(text, "test.toml");
  ASSERT_EQ(scene.bodies.size(), 7u);
  const std::vector<std::string> colours = {"#d9572b", "#2b7bd9", "#3fa34d", "#d9b32b",
                                            "#8e44ad", "#16a085", "#d9572b"};
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(scene.bodies[i].name, "body" + std::to_string(i + 1));
    EXPECT_EQ(to_string(scene.bodies[i].color), colours[i]) << "body " << i + 1;
  }
}

TEST(SceneLoader, ParticleSizeDefaultsToItsDrawnSize) {
  const Scene scene = parse_scene("[[body]]\nshape = \"particle\"\nmass = 0.1\n", "test.toml");
  EXPECT_EQ(scene.bodies[0].size, Vec3(0.1, 0.1, 0.1));
}

TEST(SceneLoader, AcceptsInlineArraysOfBodiesAndSubTables) {
  const Scene scene = parse_scene(R"(body = [
  { shape = "particle", mass = 1.0 },
]
)",
                                  "test.toml");
  EXPECT_EQ(scene.bodies.size(), 1u);
  const Scene sub = parse_scene(R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
[body.orientation]
axis = [0, 0, 1]
degrees = 90
)",
                                "test.toml");
  EXPECT_TRUE((sub.bodies[0].orientation * Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-12));
}

// ---------------------------------------------------------------------------------------------
// TOML itself

TEST(SceneLoader, TomlSyntaxErrorReportsItsPlace) {
  EXPECT_TRUE(FailsAt("[simulation]\nduration = = 4\n", 2, 12, "TOML syntax error"));
  EXPECT_TRUE(FailsAt("[simulation]\ndt = 1\ndt = 2\n", 3, 6, "TOML syntax error"));
  EXPECT_TRUE(FailsAt("[render\n", 1, 8, "TOML syntax error in table header"));
}

// ---------------------------------------------------------------------------------------------
// Unknown keys

TEST(SceneLoader, UnknownKeySuggestsClosest) {
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
restitusion = 0.5
)",
                      5, 1,
                      R"(unknown key "restitusion" in [[body]] (did you mean "restitution"?))"));
}

TEST(SceneLoader, UnknownKeyWithNothingCloseHasNoSuggestion) {
  EXPECT_TRUE(FailsAt(with_box("[render]\n  supersampling = 4\n"), 2, 3,
                      R"(unknown key "supersampling" in [render])"));
  try {
    parse_scene(with_box("[render]\nsupersampling = 4\n"), "test.toml");
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("did you mean"), std::string::npos) << e.what();
  }
}

TEST(SceneLoader, UnknownKeyIsReportedInEveryTable) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nintegrater = \"rk4\"\n"), 2, 1,
                      R"(unknown key "integrater" in [simulation] (did you mean "integrator"?))"));
  EXPECT_TRUE(FailsAt(with_box("[floor]\nfriciton = 0.1\n"), 2, 1,
                      R"(unknown key "friciton" in [floor] (did you mean "friction"?))"));
  EXPECT_TRUE(FailsAt(with_box("[camera]\nfov = 30\n"), 2, 1, R"(unknown key "fov" in [camera])"));
  EXPECT_TRUE(FailsAt(with_box("[light]\nshadow = false\n"), 2, 1,
                      R"(unknown key "shadow" in [light] (did you mean "shadows"?))"));
}

TEST(SceneLoader, UnknownKeyInsideOrientation) {
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
orientation = { axis = [1, 0, 0], degree = 10 }
)",
                      5, 35,
                      R"(unknown key "degree" in [[body]] orientation (did you mean "degrees"?))"));
}

TEST(SceneLoader, UnknownKeyComingFirstInTheFileIsReported) {
  // toml++ keeps keys sorted; the error must still follow the file, top to bottom.
  EXPECT_TRUE(FailsAt(with_box("[render]\nzoom = 2\nalpha = 1\n"), 2, 1, "\"zoom\""));
}

TEST(SceneLoader, UnknownTableSuggestsClosest) {
  EXPECT_TRUE(FailsAt(with_box("[simulaton]\nduration = 1.0\n"), 1, 2,
                      R"(unknown table [simulaton] (did you mean "simulation"?))"));
  EXPECT_TRUE(FailsAt("[[bodys]]\nshape = \"box\"\n", 1, 3,
                      R"(unknown table [[bodys]] (did you mean "body"?))"));
  EXPECT_TRUE(FailsAt(with_box("duration = 4.0\n"), 1, 1, R"(unknown top-level key "duration")"));
}

TEST(SceneLoader, TopLevelTableMustBeATable) {
  EXPECT_TRUE(
      FailsAt(with_box("render = 60\n"), 1, 10, "[render] must be a table, got an integer"));
}

// ---------------------------------------------------------------------------------------------
// Types and finiteness

TEST(SceneLoader, RejectsAWrongType) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nduration = \"4\"\n"), 2, 12,
                      "duration in [simulation] must be a number, got a string"));
  EXPECT_TRUE(FailsAt(with_box("[light]\nshadows = 1\n"), 2, 11,
                      "shadows in [light] must be true or false, got an integer"));
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nintegrator = 4\n"), 2, 14,
                      "integrator in [simulation] must be a string, got an integer"));
}

TEST(SceneLoader, RejectsARealWhereAnIntegerIsExpected) {
  EXPECT_TRUE(FailsAt(with_box("[render]\nfps = 60.0\n"), 2, 7,
                      "fps in [render] must be an integer, got a floating-point number"));
}

TEST(SceneLoader, RejectsNonFiniteNumbers) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\ndt = nan\n"), 2, 6,
                      "dt in [simulation] must be finite, got nan"));
  EXPECT_TRUE(FailsAt(with_box("[simulation]\ngravity = [0.0, -inf, 0.0]\n"), 2, 17,
                      "element 2 of gravity in [simulation] must be finite, got -inf"));
}

TEST(SceneLoader, VectorMustBeThreeNumbers) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\ngravity = [0.0, -9.81]\n"), 2, 11,
                      "gravity in [simulation] must be an array of 3 numbers, got 2 elements"));
  EXPECT_TRUE(FailsAt(with_box("[simulation]\ngravity = -9.81\n"), 2, 11,
                      "gravity in [simulation] must be an array of 3 numbers, got a floating"));
  EXPECT_TRUE(FailsAt(with_box("[camera]\ntarget = [0, \"1\", 0]\n"), 2, 14,
                      "element 2 of target in [camera] must be a number, got a string"));
}

// ---------------------------------------------------------------------------------------------
// [simulation]

TEST(SceneLoader, DurationMustBePositiveAndBounded) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nduration = 0\n"), 2, 12,
                      "duration in [simulation] must be in (0, 1e+06], got 0"));
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nduration = 2e6\n"), 2, 12, "got 2e+06"));
}

TEST(SceneLoader, DtMustBePositive) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\ndt = -0.001\n"), 2, 6,
                      "dt in [simulation] must be > 0, got -0.001"));
}

TEST(SceneLoader, DtMustNotExceedDuration) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nduration = 1.0\ndt = 2.0\n"), 3, 6,
                      "dt in [simulation] (2 s) must not exceed duration (1 s)"));
  // Without a dt in the file, the short duration is what the user wrote wrong.
  EXPECT_TRUE(
      FailsAt(with_box("[simulation]\nduration = 0.0005\n"), 2, 12, "must not exceed duration"));
}

TEST(SceneLoader, UnknownIntegratorListsTheChoices) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nintegrator = \"rk5\"\n"), 2, 14,
                      R"(unknown integrator "rk5" (expected one of: euler, symplectic-euler, )"
                      R"(midpoint, rk4, adaptive))"));
}

TEST(SceneLoader, UnknownRotationListsTheChoices) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nrotation = \"euler-angles\"\n"), 2, 12,
                      R"(unknown rotation "euler-angles" (expected one of: quaternion, matrix))"));
}

TEST(SceneLoader, DragsMustBeNonNegative) {
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nlinear_drag = -0.1\n"), 2, 15,
                      "linear_drag in [simulation] must be >= 0, got -0.1"));
  EXPECT_TRUE(FailsAt(with_box("[simulation]\nangular_drag = -1\n"), 2, 16,
                      "angular_drag in [simulation] must be >= 0, got -1"));
}

// ---------------------------------------------------------------------------------------------
// [floor]

TEST(SceneLoader, FloorRestitutionMustBeWithinZeroAndOne) {
  EXPECT_TRUE(FailsAt(with_box("[floor]\nrestitution = 1.5\n"), 2, 15,
                      "restitution in [floor] must be in [0, 1], got 1.5"));
  EXPECT_TRUE(FailsAt(with_box("[floor]\nrestitution = -0.1\n"), 2, 15, "got -0.1"));
}

TEST(SceneLoader, FloorFrictionMustBeNonNegative) {
  EXPECT_TRUE(FailsAt(with_box("[floor]\nfriction = -0.5\n"), 2, 12,
                      "friction in [floor] must be >= 0, got -0.5"));
}

// ---------------------------------------------------------------------------------------------
// [render]

TEST(SceneLoader, FpsMustBeBetweenOneAndAThousand) {
  EXPECT_TRUE(FailsAt(with_box("[render]\nfps = 0\n"), 2, 7,
                      "fps in [render] must be an integer in [1, 1000], got 0"));
  EXPECT_TRUE(FailsAt(with_box("[render]\nfps = 1001\n"), 2, 7, "got 1001"));
}

TEST(SceneLoader, ImageSizeMustBeBetweenOneAnd16384) {
  EXPECT_TRUE(FailsAt(with_box("[render]\nwidth = 0\n"), 2, 9,
                      "width in [render] must be an integer in [1, 16384], got 0"));
  EXPECT_TRUE(FailsAt(with_box("[render]\nheight = 16385\n"), 2, 10,
                      "height in [render] must be an integer in [1, 16384], got 16385"));
}

TEST(SceneLoader, MsaaMustBeBetweenZeroAnd16) {
  EXPECT_TRUE(FailsAt(with_box("[render]\nmsaa = 32\n"), 2, 8,
                      "msaa in [render] must be an integer in [0, 16], got 32"));
  EXPECT_TRUE(FailsAt(with_box("[render]\nmsaa = -1\n"), 2, 8, "got -1"));
}

TEST(SceneLoader, ColoursMustBeHashAndSixHexDigits) {
  EXPECT_TRUE(FailsAt(with_box("[render]\nbackground = \"white\"\n"), 2, 14,
                      R"(background in [render] must be a colour "#rrggbb" (6 hex digits), )"
                      R"(got "white")"));
  EXPECT_TRUE(FailsAt(with_box("[render]\nbackground = \"#12345\"\n"), 2, 14, R"(got "#12345")"));
  EXPECT_TRUE(FailsAt(with_box("[render]\nbackground = \"#12345g\"\n"), 2, 14, "#rrggbb"));
  EXPECT_TRUE(FailsAt(with_box("[render]\nbackground = \"#+12345\"\n"), 2, 14, "#rrggbb"));
  EXPECT_TRUE(FailsAt(R"([[body]]
shape = "box"
size = [1, 1, 1]
mass = 1
color = "d9572b"
)",
                      5, 9, R"(color in [[body]] must be a colour "#rrggbb")"));
}

// ---------------------------------------------------------------------------------------------
// [camera] and [light]

TEST(SceneLoader, CameraPositionMustDifferFromTarget) {
  EXPECT_TRUE(FailsAt(with_box("[camera]\nposition = [1, 2, 3]\ntarget = [1, 2, 3]\n"), 3, 10,
                      "target in [camera] must differ from position"));
}

TEST(SceneLoader, RecordsWhichCameraKeysTheSceneStates) {
  // No position: the camera frames the run (camera_framing.hpp); what was stated is kept.
  const Scene none = parse_scene(with_box(""), "test.toml");
  EXPECT_FALSE(none.camera.position_given);
  EXPECT_FALSE(none.camera.target_given);
  EXPECT_FALSE(none.camera.ortho_height_given);
  EXPECT_FALSE(none.camera.framed);
  const Scene some =
      parse_scene(with_box("[camera]\ntarget = [0, 1, 0]\northo_height = 3\n"), "test.toml");
  EXPECT_FALSE(some.camera.position_given);
  EXPECT_TRUE(some.camera.target_given);
  EXPECT_TRUE(some.camera.ortho_height_given);
  const Scene all =
      parse_scene(with_box("[camera]\nposition = [1, 2, 3]\ntarget = [0, 1, 0]\n"), "test.toml");
  EXPECT_TRUE(all.camera.position_given);
  EXPECT_TRUE(all.camera.target_given);
}

TEST(SceneLoader, FramedCameraUpMustNotBeParallelToTheFramingDirection) {
  // Without a position the camera looks along -(5, 3, 6): an up along it is no up at all.
  EXPECT_TRUE(FailsAt(with_box("[camera]\nup = [5, 3, 6]\n"), 2, 6,
                      "up in [camera] must be non-zero and not parallel"));
}

TEST(SceneLoader, CameraUpMustNotBeParallelToTheViewDirection) {
  EXPECT_TRUE(FailsAt(with_box("[camera]\nposition = [0, 5, 0]\ntarget = [0, 0, 0]\n"
                               "up = [0, 2, 0]\n"),
                      4, 6, "up in [camera] must be non-zero and not parallel"));
  EXPECT_TRUE(FailsAt(with_box("[camera]\nup = [0, 0, 0]\n"), 2, 6, "must be non-zero"));
  // A camera straight overhead with the default up: the target the user wrote is blamed.
  EXPECT_TRUE(FailsAt(with_box("[camera]\nposition = [0, 9, 0]\ntarget = [0, 1, 0]\n"), 3, 10,
                      "not parallel to the view direction"));
  // A view vector that overflows to infinity must not slip through as NaN.
  EXPECT_TRUE(FailsAt(with_box("[camera]\nposition = [1e308, 0, 0]\ntarget = [-1e308, 0, 0]\n"), 3,
                      10, "not parallel to the view direction"));
}

TEST(SceneLoader, FieldOfViewMustBeWithinZeroAnd180) {
  EXPECT_TRUE(FailsAt(with_box("[camera]\nfov_deg = 0\n"), 2, 11,
                      "fov_deg in [camera] must be in (0, 180), got 0"));
  EXPECT_TRUE(FailsAt(with_box("[camera]\nfov_deg = 180\n"), 2, 11, "got 180"));
}

TEST(SceneLoader, FollowMustNameABody) {
  EXPECT_TRUE(FailsAt(with_box("[camera]\nfollow = \"bx\"\n"), 2, 10,
                      R"(follow in [camera] names no body: "bx" (did you mean "box"?))"));
}

TEST(SceneLoader, LightDirectionMustBeNonZero) {
  EXPECT_TRUE(FailsAt(with_box("[light]\ndirection = [0, 0, 0]\n"), 2, 13,
                      "direction in [light] must be non-zero"));
}

// ---------------------------------------------------------------------------------------------
// [[body]]

TEST(SceneLoader, SceneNeedsABody) {
  try {
    parse_scene("[simulation]\nduration = 1.0\n", "test.toml");
    ADD_FAILURE() << "parsed without a body";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_EQ(e.where().file, "test.toml");
    EXPECT_EQ(e.where().line, 0);  // nothing in the file to point at
    EXPECT_EQ(e.describe(), "test.toml: a scene needs at least one [[body]]");
  }
  EXPECT_TRUE(FailsAt("body = []\n", 1, 8, "a scene needs at least one [[body]]"));
  EXPECT_TRUE(FailsAt("[body]\nshape = \"box\"\n", 1, 1,
                      "body must be an array of tables, written [[body]], got a table"));
  EXPECT_TRUE(FailsAt("body = [1]\n", 1, 9, "each body must be a table"));
}

TEST(SceneLoader, BodyNameMustBeUniqueAndNonEmpty) {
  // The second "box" is the one appended by with_box, on line 7.
  EXPECT_TRUE(FailsAt(with_box("[[body]]\nname = \"box\"\nshape = \"particle\"\nmass = 1\n"), 7, 8,
                      R"(duplicate body name "box" (first used by the [[body]] on line 1))"));
  EXPECT_TRUE(FailsAt("[[body]]\nname = \"\"\nshape = \"particle\"\nmass = 1\n", 2, 8,
                      "name in [[body]] must not be empty"));
  // The default name of the second body, "body2", is already taken by the first.
  EXPECT_TRUE(
      FailsAt("[[body]]\nname = \"body2\"\nshape = \"particle\"\nmass = 1\n"
              "[[body]]\nshape = \"particle\"\nmass = 1\n",
              5, 1, "has no name and was given that default"));
}

TEST(SceneLoader, ShapeIsRequired) {
  EXPECT_TRUE(FailsAt("[[body]]\nsize = [1, 1, 1]\nmass = 1\n", 1, 1,
                      R"(missing key "shape" in [[body]] (expected one of: box, sphere, particle, mesh))"));
}

TEST(SceneLoader, UnknownShapeListsTheChoices) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"cylinder\"\nmass = 1\n", 2, 9,
                      R"(unknown shape "cylinder" (expected one of: box, sphere, particle, mesh))"));
}

TEST(SceneLoader, MeshBodyResolvesItsFileAgainstTheScenesFolder) {
  const Scene scene = parse_scene(
      "[[body]]\nshape = \"mesh\"\nmesh = \"models/bunny.obj\"\ndensity = 1000\n"
      "scale = [0.01, 0.02, 0.03]\nrepair = \"orient\"\n",
      "scenes/test.toml");
  const BodySpec& b = scene.bodies.at(0);
  EXPECT_EQ(b.shape, Shape::Mesh);
  EXPECT_EQ(b.mesh, "scenes/models/bunny.obj");
  EXPECT_EQ(b.mesh_where.line, 3);
  EXPECT_EQ(b.scale, Vec3(0.01, 0.02, 0.03));
  EXPECT_EQ(b.repair, MeshRepair::Orient);
  EXPECT_EQ(parse_scene("[[body]]\nshape = \"mesh\"\nmesh = \"/m/a.stl\"\nmass = 1\nscale = 2\n",
                        "s/t.toml")
                .bodies.at(0)
                .scale,
            Vec3::Constant(2.0));
}

TEST(SceneLoader, MeshBodyNeedsItsFileAndNoSize) {
  EXPECT_TRUE(
      FailsAt("[[body]]\nshape = \"mesh\"\nmass = 1\n", 1, 1, R"(missing key "mesh" in [[body]])"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"mesh\"\nmesh = \"a.obj\"\nmass = 1\nsize = [1, 1, 1]\n",
                      5, 8, "size in [[body]] does not apply to a mesh"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"mesh\"\nmesh = \"a.obj\"\nmass = 1\nrepair = \"fix\"\n",
                      5, 10, R"(expected one of: none, orient, hull)"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"mesh\"\nmesh = \"a.obj\"\nmass = 1\nscale = \"big\"\n",
                      5, 9, "scale in [[body]] must be a number or an array [x, y, z]"));
  EXPECT_TRUE(
      FailsAt("[[body]]\nshape = \"mesh\"\nmesh = \"a.obj\"\nmass = 1\nscale = [1, -1, 1]\n", 5, 13,
              "element 2 of scale in [[body]] must be > 0, got -1"));
}

TEST(SceneLoader, MeshKeysAreOnlyForMeshes) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\nmesh = \"a.obj\"\n",
                      5, 8, R"(mesh in [[body]] applies only to shape = "mesh")"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\nscale = 2\n", 5, 9,
                      R"(scale in [[body]] applies only to shape = "mesh")"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\nrepair = \"hull\"\n",
                      5, 10, R"(repair in [[body]] applies only to shape = "mesh")"));
}

TEST(SceneLoader, ScaleMustBePositive) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\nscale = 0\n", 5, 9,
                      "scale in [[body]] must be > 0, got 0"));
}

TEST(SceneLoader, BoxNeedsAPositiveSize) {
  EXPECT_TRUE(FailsAt("\n[[body]]\nshape = \"box\"\nmass = 1\n", 2, 1,
                      R"(missing key "size" in [[body]])"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 0, 1]\nmass = 1\n", 3, 12,
                      "element 2 of size in [[body]] must be > 0, got 0"));
}

TEST(SceneLoader, ParticleSizeMustBePositiveToo) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"particle\"\nsize = [0.1, 0.1, -0.1]\nmass = 1\n", 3, 19,
                      "element 3 of size in [[body]] must be > 0, got -0.1"));
}

TEST(SceneLoader, BodyNeedsExactlyOneOfMassAndDensity) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\n", 1, 1,
                      R"(missing key "mass" or "density" in [[body]])"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\ndensity = 2\n", 5, 11,
                      "give mass or density in [[body]], not both"));
}

TEST(SceneLoader, MassAndDensityMustBePositive) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 0\n", 4, 8,
                      "mass in [[body]] must be > 0, got 0"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\ndensity = -1000\n", 4, 11,
                      "density in [[body]] must be > 0, got -1000"));
}

TEST(SceneLoader, ParticleHasNoDensityNorRotation) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"particle\"\ndensity = 1000\n", 3, 11,
                      "density in [[body]] does not apply to a particle: it has no volume"));
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"particle\"\nmass = 1\nangular_velocity = [0, 1, 0]\n", 4,
                      20, "angular_velocity in [[body]] does not apply to a particle"));
  EXPECT_TRUE(
      FailsAt("[[body]]\nshape = \"particle\"\nmass = 1\n"
              "orientation = { axis = [0, 1, 0], degrees = 5 }\n",
              4, 15, "orientation in [[body]] does not apply to a particle"));
}

TEST(SceneLoader, OrientationNeedsANonZeroAxisAndFiniteDegrees) {
  const std::string body = "[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\n";
  EXPECT_TRUE(FailsAt(body + "orientation = { axis = [0, 0, 0], degrees = 5 }\n", 5, 24,
                      "axis in [[body]] orientation must be non-zero"));
  EXPECT_TRUE(FailsAt(body + "orientation = { axis = [0, 1, 0], degrees = inf }\n", 5, 45,
                      "degrees in [[body]] orientation must be finite, got inf"));
  EXPECT_TRUE(FailsAt(body + "orientation = { axis = [0, 1, 0] }\n", 5, 15,
                      R"(missing key "degrees" in [[body]] orientation)"));
  EXPECT_TRUE(FailsAt(body + "orientation = { degrees = 5 }\n", 5, 15,
                      R"(missing key "axis" in [[body]] orientation)"));
  EXPECT_TRUE(FailsAt(body + "orientation = [0, 1, 0]\n", 5, 15,
                      "orientation in [[body]] must be a table like { axis = [x, y, z], "
                      "degrees = d }, got an array"));
}

TEST(SceneLoader, BodyRestitutionMustBeWithinZeroAndOne) {
  EXPECT_TRUE(FailsAt("[[body]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1\nrestitution = 2\n", 5,
                      15, "restitution in [[body]] must be in [0, 1], got 2"));
}

TEST(SceneLoader, ErrorsDescribeThemselvesWithFileLineAndColumn) {
  try {
    parse_scene(with_box("[render]\nfps = 0\n"), "scenes/drop.toml");
    ADD_FAILURE() << "parsed";
  } catch (const Error& e) {
    EXPECT_EQ(e.describe(),
              "scenes/drop.toml:2:7: fps in [render] must be an integer in [1, 1000], got 0");
  }
}

// ---------------------------------------------------------------------------------------------
// Files

TEST(SceneLoader, LoadsAFileByPath) {
  const std::filesystem::path path =
      std::filesystem::path(testing::TempDir()) / "tumble_scene_loader_test.toml";
  const std::string text = "[[body]]\r\nshape = \"particle\"\r\nmass = 2\r\n";
  std::ofstream(path, std::ios::binary) << text;
  const Scene scene = load_scene_file(path);
  EXPECT_EQ(scene.source_name, path.string());
  EXPECT_EQ(scene.source_text, text);  // read in binary: CRLF kept, byte for byte
  EXPECT_EQ(scene.stem, "tumble_scene_loader_test");
  EXPECT_EQ(scene.bodies.at(0).mass, 2.0);
  std::filesystem::remove(path);
}

TEST(SceneLoader, MissingFileIsBadInputWithoutALocation) {
  try {
    load_scene_file("no/such/scene.toml");
    ADD_FAILURE() << "loaded a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_EQ(e.where().file, "");
    EXPECT_EQ(e.where().line, 0);
    EXPECT_EQ(std::string(e.what()),
              "cannot read scene file \"no/such/scene.toml\": No such file or directory");
  }
}

TEST(SceneLoader, DirectoryIsBadInput) {
  try {
    load_scene_file(testing::TempDir());
    ADD_FAILURE() << "loaded a directory";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_NE(std::string(e.what()).find("it is a directory"), std::string::npos) << e.what();
  }
}

TEST(SceneLoader, ErrorsInAFilePointIntoIt) {
  const std::filesystem::path path =
      std::filesystem::path(testing::TempDir()) / "tumble_scene_loader_bad.toml";
  std::ofstream(path, std::ios::binary) << "[[body]]\nshape = \"cube\"\n";
  try {
    load_scene_file(path);
    ADD_FAILURE() << "loaded a bad scene";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().file, path.string());
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().column, 9);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

Scene parse_render(const std::string& render_table) {
  return parse_scene(render_table + R"(
[[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
)",
                     "aa.toml");
}

TEST(SceneLoader, AntialiasDefaultsToFxaa) {
  EXPECT_EQ(parse_render("").render.antialias, Antialias::Fxaa);
}

TEST(SceneLoader, MsaaIsTheSampleCountOfAntialiasMsaaOnly) {
  // SPEC: antialias defaults to "fxaa"; msaa is the number of samples when antialias = "msaa".
  const Scene alone = parse_render("[render]\nmsaa = 2\n");
  EXPECT_EQ(alone.render.antialias, Antialias::Fxaa);
  EXPECT_EQ(alone.render.msaa, 2);
  EXPECT_EQ(parse_render("[render]\nmsaa = 0\n").render.antialias, Antialias::Fxaa);
  const Scene both = parse_render("[render]\nantialias = \"msaa\"\nmsaa = 2\n");
  EXPECT_EQ(both.render.antialias, Antialias::Msaa);
  EXPECT_EQ(both.render.msaa, 2);
  EXPECT_EQ(parse_render("[render]\nantialias = \"none\"\nmsaa = 4\n").render.antialias,
            Antialias::None);
}

TEST(SceneLoader, UnknownAntialiasIsRejectedWithTheChoices) {
  try {
    parse_render("[render]\nantialias = \"ssaa\"\n");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 2);
    EXPECT_NE(std::string(e.what()).find("fxaa, msaa, none"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tumble
