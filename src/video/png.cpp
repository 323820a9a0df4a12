#include "tumble/png.hpp"

#include <png.h>

#include <cassert>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

// libpng reports an error by longjmp-ing back to the last setjmp. To keep that well defined in
// C++, the functions that call setjmp (encode, decode_header, decode_rows) hold only plain data,
// and so do the callbacks libpng calls; every object with a destructor (the file, the image, the
// libpng structs' owners) lives in a caller, whose frame a longjmp never crosses.

// Where the error callback leaves libpng's message for the caller to throw.
struct PngFailure {
  char message[256] = {};
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* failure = static_cast<PngFailure*>(png_get_error_ptr(png));
  std::snprintf(failure->message, sizeof failure->message, "%s", message);
  png_longjmp(png, 1);
}

// Warnings are recoverable (e.g. a bad ancillary chunk that libpng skips); stderr stays clean.
void on_png_warning(png_structp, png_const_charp) {}

// Owns a libpng read or write struct and its info struct.
enum class PngDirection { Read, Write };

template <PngDirection direction>
class PngStructs {
 public:
  explicit PngStructs(PngFailure* failure)
      : png_(direction == PngDirection::Write
                 ? png_create_write_struct(PNG_LIBPNG_VER_STRING, failure, on_png_error,
                                           on_png_warning)
                 : png_create_read_struct(PNG_LIBPNG_VER_STRING, failure, on_png_error,
                                          on_png_warning)),
        info_(png_ ? png_create_info_struct(png_) : nullptr) {}
  ~PngStructs() {
    if constexpr (direction == PngDirection::Write)
      png_destroy_write_struct(&png_, &info_);
    else
      png_destroy_read_struct(&png_, &info_, nullptr);
  }
  PngStructs(const PngStructs&) = delete;
  PngStructs& operator=(const PngStructs&) = delete;

  bool ok() const { return png_ && info_; }
  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  png_structp png_;
  png_infop info_;
};
using PngWriteStructs = PngStructs<PngDirection::Write>;
using PngReadStructs = PngStructs<PngDirection::Read>;

// ---- writing ----

void write_to_stream(png_structp png, png_bytep data, size_t size) {
  auto* out = static_cast<std::ostream*>(png_get_io_ptr(png));
  out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!*out) png_error(png, "write failed (disk full?)");
}

// AtomicFile::commit() flushes once at the end; flushing per chunk would only cost time.
void flush_nothing(png_structp) {}

// Encodes `image` into `out`. Returns false, with libpng's message in the PngFailure, on error.
bool encode(png_structp png, png_infop info, const Image* image, const PngOptions* options,
            std::ostream* out) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, out, write_to_stream, flush_nothing);
  const bool rgba = options->alpha && image->channels == 4;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image->width),
               static_cast<png_uint_32>(image->height), 8,
               rgba ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (options->packing == PngOptions::Packing::Fast) {
    // Level 1 and no row filter: 3-4 ms per 720p frame against 16-18 ms for the default
    // adaptive filter (PLATFORM.md); the files are larger, which frames on their way to a video
    // can afford.
    png_set_compression_level(png, 1);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  } else {
    // A figure written once: every filter tried per row, the strongest deflate.
    png_set_compression_level(png, 9);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  }
  png_write_info(png, info);
  // RGBA rows written as RGB: libpng drops the fourth byte of each pixel itself, so no converted
  // copy is made.
  if (image->channels == 4 && !rgba) png_set_filler(png, 0, PNG_FILLER_AFTER);
  for (int y = 0; y < image->height; ++y) png_write_row(png, image->row(y));
  png_write_end(png, nullptr);
  return true;
}

// ---- reading ----

// The whole file in memory: libpng reads from it, and running out of bytes is a clean error.
struct MemorySource {
  const unsigned char* data;
  size_t size;
  size_t offset;
};

void read_from_memory(png_structp png, png_bytep out, size_t size) {
  auto* source = static_cast<MemorySource*>(png_get_io_ptr(png));
  if (source->size - source->offset < size) png_error(png, "the file is truncated");
  std::memcpy(out, source->data + source->offset, size);
  source->offset += size;
}

struct PngLayout {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int channels = 0;
};

// Reads the header and sets up the conversion to 8-bit RGB or RGBA. Returns false on error.
bool decode_header(png_structp png, png_infop info, MemorySource* source, PngLayout* layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, source, read_from_memory);
  png_read_info(png, info);
  const int color_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  // Pixel values are taken as stored: no gamma correction, so a file reads back as written.
  if (bit_depth == 16) png_set_scale_16(png);  // rounds v * 255 / 65535, unlike strip_16
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  // Transparency given as a tRNS chunk becomes an alpha channel, as alpha in the file would.
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (color_type == PNG_COLOR_TYPE_GRAY || color_type == PNG_COLOR_TYPE_GRAY_ALPHA)
    png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  layout->width = png_get_image_width(png, info);
  layout->height = png_get_image_height(png, info);
  layout->channels = png_get_channels(png, info);
  return true;
}

// Decodes the pixels into `rows` (one pointer per row) and checks the rest of the file.
bool decode_rows(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

[[noreturn]] void cannot_read(const fs::path& path, const std::string& why) {
  throw Error(ErrorKind::BadInput, "cannot read PNG \"" + path.string() + "\": " + why);
}

std::string read_whole_file(const fs::path& path) {
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) cannot_read(path, errno ? std::generic_category().message(errno) : "cannot open it");
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) cannot_read(path, "read failed");
  return bytes;
}

// Decoded images above this many bytes are refused rather than allocated: a corrupt header can
// claim up to 10^6 x 10^6 pixels (libpng's default limits), which would only end in bad_alloc.
constexpr size_t kMaxDecodedBytes = size_t{1} << 31;

}  // namespace

void write_png(const fs::path& path, const Image& image, const PngOptions& options) {
  assert(image.width > 0 && image.height > 0);
  assert(image.channels == 3 || image.channels == 4);
  assert(image.pixels.size() == image.stride() * static_cast<size_t>(image.height));
  AtomicFile file(path);
  PngFailure failure;
  PngWriteStructs png(&failure);
  if (!png.ok()) throw Error(ErrorKind::Environment, "libpng: out of memory");
  if (!encode(png.png(), png.info(), &image, &options, &file.stream()))
    throw Error(ErrorKind::Environment,
                "cannot write \"" + path.string() + "\": libpng: " + failure.message);
  file.commit();
}

Image read_png(const fs::path& path) {
  const std::string bytes = read_whole_file(path);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  constexpr size_t kSignatureBytes = 8;
  if (bytes.size() < kSignatureBytes || png_sig_cmp(data, 0, kSignatureBytes) != 0)
    cannot_read(path, "not a PNG file");

  PngFailure failure;
  PngReadStructs png(&failure);
  if (!png.ok()) throw Error(ErrorKind::Environment, "libpng: out of memory");
  MemorySource source{data, bytes.size(), 0};
  PngLayout layout;
  if (!decode_header(png.png(), png.info(), &source, &layout)) cannot_read(path, failure.message);
  assert(layout.channels == 3 || layout.channels == 4);
  if (size_t{layout.width} * layout.height * static_cast<size_t>(layout.channels) >
      kMaxDecodedBytes)
    cannot_read(path, "image of " + std::to_string(layout.width) + "x" +
                          std::to_string(layout.height) + " pixels is too large");

  Image image(static_cast<int>(layout.width), static_cast<int>(layout.height), layout.channels);
  std::vector<png_bytep> rows(layout.height);
  for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = image.row(static_cast<int>(y));
  if (!decode_rows(png.png(), png.info(), rows.data())) cannot_read(path, failure.message);
  return image;
}

}  // namespace tumble
