// tumble info: versions, EGL devices, the GL context tumble would render with, H.264 encoders.
#include <cstdio>

#include "commands.hpp"
#include "tumble/egl_context.hpp"
#include "tumble/mp4_writer.hpp"
#include "version_text.hpp"

namespace tumble::cli {

void add_info_command(CLI::App& app) {
  app.add_subcommand("info", "Versions, EGL devices, GL renderer and available H.264 encoders");
}

int run_info() {
  std::printf("%s\n", version_text().c_str());  // tumble X.Y.Z, then its libraries
  const auto devices = EglContext::list_devices();
  std::printf("EGL devices: %zu\n", devices.size());
  for (const auto& d : devices) std::printf("  %s\n", d.c_str());
  std::printf("H.264 encoders in FFmpeg:");
  for (const auto& e : Mp4Writer::available_h264_encoders()) std::printf(" %s", e.c_str());
  std::printf("\n");
  // Compiled in is not usable: a hardware encoder needs its device and driver too.
  std::printf("H.264 encoders usable here:");
  for (const auto& e : Mp4Writer::usable_h264_encoders()) std::printf(" %s", e.c_str());
  const std::string chosen = Mp4Writer::auto_h264_encoder();
  std::printf("\nencoder auto: %s\n", chosen.empty() ? "(none opens)" : chosen.c_str());
  const EglContext gl;  // throws Environment (exit 3) with every attempt listed
  const GlInfo& i = gl.info();
  std::printf("EGL platform: %s\nEGL vendor: %s\nEGL version: %s\n", i.platform.c_str(),
              i.egl_vendor.c_str(), i.egl_version.c_str());
  std::printf("GL vendor: %s\nGL renderer: %s\nGL version: %s\n", i.gl_vendor.c_str(),
              i.gl_renderer.c_str(), i.gl_version.c_str());
  return 0;
}

}  // namespace tumble::cli
