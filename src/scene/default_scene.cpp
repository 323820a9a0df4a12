#include "tumble/scene.hpp"

namespace tumble {
namespace {

// The same text as assets/scenes/default.toml, embedded so the binary needs no file to run;
// a unit test fails if the two drift apart.
constexpr std::string_view kDefaultScene = R"toml(# The built-in scene, used when none is given:
# the seed's experiment, a unit box dropped with a tilt and a spin onto a floor.
# Kept identical to the copy embedded in src/scene/default_scene.cpp.

[simulation]
duration = 4.0
dt = 0.001
integrator = "rk4"

[floor]
restitution = 0.5

[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
orientation = { axis = [1.0, 0.0, 1.0], degrees = 30.0 }
angular_velocity = [0.0, 0.0, 2.0]
color = "#d9572b"
)toml";

}  // namespace

Scene default_scene() {
  Scene scene = parse_scene(kDefaultScene, "<default>");
  scene.stem = "default";
  return scene;
}

}  // namespace tumble
