// The video layer's libraries, as loaded at run time: FFmpeg's (each reports its packed
// major.minor.micro) and libpng.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavfilter/avfilter.h>
#include <libavformat/avformat.h>
#include <libavutil/avutil.h>
#include <libswscale/swscale.h>
}
#include <png.h>

#include "tumble/library_versions.hpp"

namespace tumble::video {
namespace {

std::string dotted(unsigned packed) {
  return std::to_string(AV_VERSION_MAJOR(packed)) + "." + std::to_string(AV_VERSION_MINOR(packed)) +
         "." + std::to_string(AV_VERSION_MICRO(packed));
}

LibraryVersion ffmpeg(const char* name, unsigned runtime, unsigned built) {
  return {name, runtime_version(dotted(runtime), dotted(built))};
}

}  // namespace

LibraryVersions library_versions() {
  return {ffmpeg("libavcodec", avcodec_version(), LIBAVCODEC_VERSION_INT),
          ffmpeg("libavformat", avformat_version(), LIBAVFORMAT_VERSION_INT),
          ffmpeg("libavfilter", avfilter_version(), LIBAVFILTER_VERSION_INT),
          ffmpeg("libswscale", swscale_version(), LIBSWSCALE_VERSION_INT),
          ffmpeg("libavutil", avutil_version(), LIBAVUTIL_VERSION_INT),
          {"libpng", runtime_version(png_get_libpng_ver(nullptr), PNG_LIBPNG_VER_STRING)}};
}

}  // namespace tumble::video
