#include "tumble/egl_context.hpp"

#define EGL_EGLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstring>
#include <string_view>

#include "tumble/error.hpp"

namespace tumble {

struct EglContext::Handles {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  ~Handles() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

namespace {

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + std::to_string(code);
  }
}

bool has_extension(const char* list, std::string_view name) {
  if (!list) return false;
  std::string_view all(list);
  for (std::size_t pos = 0; (pos = all.find(name, pos)) != std::string_view::npos; ++pos) {
    const bool starts = pos == 0 || all[pos - 1] == ' ';
    const bool ends = pos + name.size() == all.size() || all[pos + name.size()] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

// "there is only 1 EGL device", "there are only 2 EGL devices", "there is no EGL device".
std::string egl_device_count_text(std::size_t count) {
  if (count == 0) return "there is no EGL device";
  if (count == 1) return "there is only 1 EGL device";
  return "there are only " + std::to_string(count) + " EGL devices";
}

std::vector<EGLDeviceEXT> query_devices() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_device_enumeration") &&
      !has_extension(client, "EGL_EXT_device_base"))
    return {};
  auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (!query) return {};
  EGLint count = 0;
  if (!query(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  query(count, devices.data(), &count);
  devices.resize(static_cast<std::size_t>(count));
  return devices;
}

const char* device_extensions(EGLDeviceEXT device) {
  auto query = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  return query ? query(device, EGL_EXTENSIONS) : nullptr;
}

bool is_software(EGLDeviceEXT device) {
  return has_extension(device_extensions(device), "EGL_MESA_device_software");
}

// Initialises `display`, binds desktop OpenGL (without it Mesa gives GLES) and makes a core
// 3.3+ context current with no surface. Returns an empty string on success, else why not.
std::string try_display(EGLDisplay display, EglContext::Handles& h) {
  if (display == EGL_NO_DISPLAY) return "no display (" + egl_error_name(eglGetError()) + ")";
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor))
    return "eglInitialize failed (" + egl_error_name(eglGetError()) + ")";
  h.display = display;
  if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    return "no EGL_KHR_surfaceless_context";
  if (!eglBindAPI(EGL_OPENGL_API)) return "desktop OpenGL not available";
  // A headless config: any surface type (the default window bit matches nothing here).
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attribs, &config, 1, &configs) || configs < 1) {
    const EGLint any[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    if (!eglChooseConfig(display, any, &config, 1, &configs) || configs < 1)
      return "no OpenGL-capable EGL config";
  }
  // Ask for 3.3 core: drivers return their newest compatible core version (4.5 on llvmpipe);
  // asking 4.6 fails with EGL_BAD_MATCH there.
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    3,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  h.context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (h.context == EGL_NO_CONTEXT)
    return "no OpenGL 3.3 core context (" + egl_error_name(eglGetError()) + ")";
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, h.context))
    return "eglMakeCurrent failed (" + egl_error_name(eglGetError()) + ")";
  return {};
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

}  // namespace

EglContext::EglContext(int device) {
  std::string tried;
  auto attempt = [&](const std::string& label, auto make_display) {
    auto h = std::make_unique<Handles>();
    const std::string why = try_display(make_display(), *h);
    if (why.empty()) {
      handles_ = std::move(h);
      info_.platform = label;
      return true;
    }
    tried += "\n  " + label + ": " + why;
    return false;
  };
  const std::vector<EGLDeviceEXT> devices = query_devices();
  auto device_display = [&](std::size_t i) {
    return [&, i] { return eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr); };
  };
  bool ok = false;
  if (device >= 0) {
    if (static_cast<std::size_t>(device) >= devices.size())
      throw Error(ErrorKind::Environment, "--egl-device " + std::to_string(device) + ": " +
                                              egl_device_count_text(devices.size()) +
                                              " (see 'tumble info')");
    ok = attempt("device " + std::to_string(device), device_display(std::size_t(device)));
  } else {
    // GPUs first; then Mesa surfaceless (llvmpipe); then a software device as the last resort.
    for (std::size_t i = 0; !ok && i < devices.size(); ++i)
      if (!is_software(devices[i])) ok = attempt("device " + std::to_string(i), device_display(i));
    if (!ok)
      ok = attempt("surfaceless", [] {
        return eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      });
    for (std::size_t i = 0; !ok && i < devices.size(); ++i)
      if (is_software(devices[i])) ok = attempt("device " + std::to_string(i), device_display(i));
  }
  if (!ok) {
    if (devices.empty()) tried += "\n  EGL device platform: no devices";
    throw Error(ErrorKind::Environment, "no usable EGL/OpenGL 3.3 context; tried:" + tried);
  }
  info_.egl_vendor = eglQueryString(handles_->display, EGL_VENDOR);
  info_.egl_version = eglQueryString(handles_->display, EGL_VERSION);
  info_.gl_vendor = gl_string(GL_VENDOR);
  info_.gl_renderer = gl_string(GL_RENDERER);
  info_.gl_version = gl_string(GL_VERSION);
}

EglContext::~EglContext() = default;

std::vector<std::string> EglContext::list_devices() {
  std::vector<std::string> out;
  const std::vector<EGLDeviceEXT> devices = query_devices();
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const char* ext = device_extensions(devices[i]);
    out.push_back(std::to_string(i) + ": " + (ext ? ext : "(no extensions)"));
  }
  return out;
}

}  // namespace tumble
