#include "texture_decode.hpp"

#include <png.h>
// jpeglib.h needs size_t and FILE declared before it.
#include <cstddef>
#include <cstdio>
#include <jpeglib.h>

#include <csetjmp>
#include <cstring>

namespace tumble::mesh_detail {
namespace {

std::string too_large(std::uint64_t w, std::uint64_t h, std::uint64_t max_pixels) {
  return std::to_string(w) + " x " + std::to_string(h) + " pixels, above the limit of " +
         std::to_string(max_pixels);
}

DecodedTexture decode_png(std::span<const std::uint8_t> bytes, std::uint64_t max_pixels) {
  DecodedTexture out;
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    out.why = std::string("not a readable PNG: ") + image.message;
    return out;
  }
  if (std::uint64_t(image.width) * image.height > max_pixels || image.width == 0 ||
      image.height == 0) {
    out.why = image.width == 0 || image.height == 0 ? "an empty image"
                                                     : too_large(image.width, image.height,
                                                                 max_pixels);
    png_image_free(&image);
    return out;
  }
  // 8-bit sRGB RGBA whatever the file holds (palette, grey, 16-bit, with or without alpha).
  image.format = PNG_FORMAT_RGBA;
  out.image.width = int(image.width);
  out.image.height = int(image.height);
  out.image.rgba.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.image.rgba.data(), 0, nullptr)) {
    out.why = std::string("a corrupt PNG: ") + image.message;
    out.image = {};
  }
  png_image_free(&image);
  return out;
}

// libjpeg reports errors by calling error_exit, which must not return: jump back out of it.
struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void jpeg_fail(j_common_ptr info) {
  auto* error = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, error->message);
  std::longjmp(error->jump, 1);
}

void jpeg_quiet(j_common_ptr, int) {}  // warnings (e.g. extra bytes) are not the user's problem

// Only plain data lives across setjmp here (the decoder's C state and a raw buffer the caller
// owns), so the longjmp skips no destructor.
bool read_jpeg(jpeg_decompress_struct& info, JpegError& error, std::span<const std::uint8_t> bytes,
               std::uint64_t max_pixels, DecodedTexture& out) {
  if (setjmp(error.jump)) return false;
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  if (std::uint64_t(info.image_width) * info.image_height > max_pixels) {
    std::snprintf(error.message, sizeof error.message, "%s",
                  too_large(info.image_width, info.image_height, max_pixels).c_str());
    return false;
  }
  info.out_color_space = JCS_RGB;  // grey and CMYK JPEGs too
  jpeg_start_decompress(&info);
  out.image.width = int(info.output_width);
  out.image.height = int(info.output_height);
  out.image.rgba.assign(std::size_t(info.output_width) * info.output_height * 4, 255);
  std::uint8_t* rgba = out.image.rgba.data();
  // One row of RGB at a time, spread into RGBA in place from the right end.
  while (info.output_scanline < info.output_height) {
    std::uint8_t* row = rgba + std::size_t(info.output_scanline) * info.output_width * 4;
    JSAMPROW rows[1] = {row};
    jpeg_read_scanlines(&info, rows, 1);
    for (std::size_t x = info.output_width; x-- > 0;) {
      row[4 * x + 2] = row[3 * x + 2];
      row[4 * x + 1] = row[3 * x + 1];
      row[4 * x + 0] = row[3 * x + 0];
      row[4 * x + 3] = 255;
    }
  }
  jpeg_finish_decompress(&info);
  return true;
}

DecodedTexture decode_jpeg(std::span<const std::uint8_t> bytes, std::uint64_t max_pixels) {
  DecodedTexture out;
  jpeg_decompress_struct info;
  JpegError error;
  std::memset(error.message, 0, sizeof error.message);
  info.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = jpeg_fail;
  error.manager.emit_message = jpeg_quiet;
  jpeg_create_decompress(&info);
  if (!read_jpeg(info, error, bytes, max_pixels, out)) {
    out.image = {};
    out.why = std::string("not a readable JPEG: ") + error.message;
  }
  jpeg_destroy_decompress(&info);
  return out;
}

}  // namespace

DecodedTexture decode_texture(std::span<const std::uint8_t> bytes, std::uint64_t max_pixels) {
  static constexpr std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0)
    return decode_png(bytes, max_pixels);
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff)
    return decode_jpeg(bytes, max_pixels);
  DecodedTexture out;
  out.why = "neither a PNG nor a JPEG (tumble reads textures in those two formats)";
  return out;
}

}  // namespace tumble::mesh_detail
