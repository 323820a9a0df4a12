#include "tumble/scene.hpp"

namespace tumble {
// assets/scenes/default.toml, embedded at build time (src/scene/default_scene_text.cpp.in).
extern const std::string_view kDefaultSceneText;

Scene default_scene() {
  Scene scene = parse_scene(kDefaultSceneText, "<default>");
  scene.stem = "default";
  return scene;
}

}  // namespace tumble
