#pragma once
// Decoding a model's texture from its bytes (a file beside the model, a data URI, a glTF buffer
// view): PNG through libpng, JPEG through libjpeg(-turbo), told apart by their signatures, not
// by a name. Never trusts the header: the pixel count is checked before anything is allocated.

#include <cstdint>
#include <span>
#include <string>

#include "tumble/mesh.hpp"

namespace tumble::mesh_detail {

/// The image, RGBA8 top-down; or, when `why` is not empty, why it could not be decoded (not a
/// PNG or JPEG, corrupt, larger than `max_pixels`).
struct DecodedTexture {
  TextureImage image;
  std::string why;
};

DecodedTexture decode_texture(std::span<const std::uint8_t> bytes, std::uint64_t max_pixels);

}  // namespace tumble::mesh_detail
