#pragma once
/// An OpenGL 3.3+ core context with no display and no window: rendering goes to framebuffer
/// objects only. Tried in order: the EGL device platform's hardware devices (GPUs), Mesa's
/// surfaceless platform (llvmpipe on CPU machines such as CI), the software EGL device.
/// `--egl-device N` picks device N of eglQueryDevicesEXT instead.

#include <memory>
#include <string>
#include <vector>

namespace tumble {

struct GlInfo {
  std::string platform;  ///< "device N" or "surfaceless"
  std::string egl_vendor, egl_version;
  std::string gl_vendor, gl_renderer, gl_version;
};

class EglContext {
 public:
  /// Creates and makes current a context; device < 0 = the first that works. Throws
  /// tumble::Error (Environment) listing every attempt and why it failed.
  explicit EglContext(int device = -1);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  const GlInfo& info() const { return info_; }

  /// One line per EGL device: index, extensions that tell what it is.
  static std::vector<std::string> list_devices();

  struct Handles;  ///< EGL display and context (defined in egl_context.cpp)

 private:
  std::unique_ptr<Handles> handles_;
  GlInfo info_;
};

}  // namespace tumble
