#include "tumble/scene.hpp"

#include <gtest/gtest.h>

namespace tumble {
namespace {

TEST(Shape, NamesAreTheOnesASceneUses) {
  EXPECT_EQ(to_string(Shape::Box), "box");
  EXPECT_EQ(to_string(Shape::Particle), "particle");
  EXPECT_EQ(to_string(Shape::Mesh), "mesh");
}

TEST(Color, PrintsAsLowerCaseHex) {
  EXPECT_EQ(to_string(Color{0xd9, 0x57, 0x2b}), "#d9572b");
  EXPECT_EQ(to_string(Color{0, 0, 0}), "#000000");
  EXPECT_EQ(to_string(Color{0xff, 0x0a, 0x01}), "#ff0a01");
}

}  // namespace
}  // namespace tumble
