#include "tumble/scene.hpp"

namespace tumble {

std::string_view to_string(Shape shape) {
  switch (shape) {
    case Shape::Box:
      return "box";
    case Shape::Particle:
      return "particle";
    case Shape::Mesh:
      return "mesh";
    case Shape::Sphere:
      return "sphere";
  }
  return "?";
}

std::string to_string(Color c) {
  constexpr std::string_view kHex = "0123456789abcdef";
  std::string s = "#";
  for (const std::uint8_t channel : {c.r, c.g, c.b}) {
    s += kHex[channel >> 4];
    s += kHex[channel & 0xf];
  }
  return s;
}

}  // namespace tumble
