#include "tumble/premultiplied.hpp"

#include <gtest/gtest.h>

#include "../test_dir.hpp"
#include "tumble/png.hpp"

namespace tumble {
namespace {

// Exact arithmetic on 8-bit values: each case states its rounding.

TEST(Premultiplied, StraightAlphaDividesByCoverage) {
  const std::uint8_t half_orange[4] = {109, 44, 22, 128};  // (217, 87, 43) at alpha 128
  std::uint8_t out[4];
  unpremultiply_pixel(half_orange, out);
  // round(109·255/128) = 217, round(44·255/128) = 88 (87.66), round(22·255/128) = 44 (43.83).
  EXPECT_EQ(out[0], 217);
  EXPECT_EQ(out[1], 88);
  EXPECT_EQ(out[2], 44);
  EXPECT_EQ(out[3], 128);
}

TEST(Premultiplied, TransparentIsZeroAndOpaqueIsUnchanged) {
  const std::uint8_t clear[4] = {0, 0, 0, 0}, solid[4] = {12, 34, 56, 255};
  std::uint8_t out[4];
  unpremultiply_pixel(clear, out);
  EXPECT_EQ(out[0] + out[1] + out[2] + out[3], 0);
  unpremultiply_pixel(solid, out);
  EXPECT_EQ(out[0], 12);
  EXPECT_EQ(out[1], 34);
  EXPECT_EQ(out[2], 56);
  EXPECT_EQ(out[3], 255);
  // Rounding can never carry a colour past 255.
  const std::uint8_t over[4] = {3, 3, 3, 2};
  unpremultiply_pixel(over, out);
  EXPECT_EQ(out[0], 255);
}

TEST(Premultiplied, CompositeOverIsTheOverOperator) {
  const std::uint8_t px[8] = {109, 44, 22, 128, 0, 0, 0, 0};
  std::uint8_t out[8];
  composite_over(px, out, 2, 223, 230, 238);
  // c + bg·(255 − a)/255: 109 + round(223·127/255) = 109 + 111 = 220.
  EXPECT_EQ(out[0], 220);
  EXPECT_EQ(out[3], 255);
  EXPECT_EQ(out[4], 223) << "nothing over the sky is the sky";
  EXPECT_EQ(out[5], 230);
  EXPECT_EQ(out[6], 238);
}

TEST(Premultiplied, FlipsGlRowsAndWritesAnRgbaPng) {
  // Two rows bottom-up: the first row in memory is the image's bottom.
  const std::uint8_t gl[16] = {255, 0,  0, 255, 0, 0, 0,   0,     // bottom: red, clear
                               0,   64, 0, 128, 0, 0, 255, 255};  // top: half green, blue
  const Image image = straight_image_from_gl_rgba(gl, 2, 2);
  ASSERT_EQ(image.channels, 4);
  EXPECT_EQ(image.row(0)[1], 128);  // round(64·255/128) = 127.5 → 128
  EXPECT_EQ(image.row(0)[3], 128);
  EXPECT_EQ(image.row(1)[0], 255);
  const auto file = test::fresh_dir("premultiplied", "png") / "a.png";
  write_png(file, image, {.alpha = true});
  const Image back = read_png(file);
  ASSERT_EQ(back.channels, 4);
  EXPECT_EQ(back.pixels, image.pixels);
}

}  // namespace
}  // namespace tumble
