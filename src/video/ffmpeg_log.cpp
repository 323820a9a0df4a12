#include <cstdarg>
#include <cstdio>
#include <string>
#include <string_view>

#include "ffmpeg_handles.hpp"

namespace tumble {
namespace {

void log_quietly(void* object, int level, const char* format, va_list args) {
  if (level > AV_LOG_ERROR || object == nullptr) return;
  // Only messages of a codec context that is being opened: try_open points its opaque at a
  // string for exactly that time. Anything else FFmpeg says is dropped.
  const AVClass* object_class = *static_cast<const AVClass**>(object);
  if (object_class != avcodec_get_class()) return;
  auto* logged = static_cast<std::string*>(static_cast<AVCodecContext*>(object)->opaque);
  if (logged == nullptr) return;
  char line[512];
  std::vsnprintf(line, sizeof line, format, args);
  std::string_view text = line;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  if (text.empty()) return;
  try {
    if (!logged->empty()) logged->append("; ");
    logged->append(text);
  } catch (...) {
    // Out of memory: the reason is lost, the error code still reports the failure. Nothing may
    // propagate into FFmpeg's C frames.
  }
}

}  // namespace

void silence_ffmpeg_log() {
  av_log_set_callback(log_quietly);
}

}  // namespace tumble
