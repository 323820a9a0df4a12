#pragma once
/// Draws a World into an off-screen framebuffer and reads the pixels back. Needs a current
/// OpenGL 3.3 core context (EglContext). The look: scene colours, a 1 m checker floor that fades
/// into the background, Blinn-Phong lighting from [light], planar shadows of the bodies on the
/// floor (exact for a plane and one extra cheap pass, instead of a shadow map), FXAA or MSAA,
/// sRGB output.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tumble/camera.hpp"  // look_at, perspective: the camera maths the renderer uses
#include "tumble/image.hpp"
#include "tumble/scene.hpp"
#include "tumble/world.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {

class Renderer {
 public:
  /// Compiles the embedded shaders and builds the framebuffers for scene.render's size and
  /// msaa (clamped to what the driver offers). Throws tumble::Error (Environment) on GL failure.
  /// How frames come back to the CPU. Async reads into pixel-pack buffers and collects them a
  /// frame later, so a GPU renders the next frame while the copy runs; on a CPU rasteriser
  /// (llvmpipe) the copy happens at once anyway and Sync saves a memcpy. Auto picks by renderer.
  enum class Readback { Auto, Sync, Async };

  /// `models`: the loaded mesh of each mesh body (uploaded once); may be null for a scene
  /// without meshes.
  explicit Renderer(const Scene& scene, Readback readback = Readback::Auto,
                    const SceneModels* models = nullptr);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders the bodies of `world` (in scene order) as they are now.
  void draw(const World& world);
  /// Reads the last drawn frame into `rgba` (resized) as RGBA rows, bottom-up as OpenGL returns
  /// them: straight into the caller's buffer, no copy.
  void read_rgba(std::vector<std::uint8_t>& rgba);
  /// Starts reading the last drawn frame back; at most two may be in flight. Drawing may go on.
  void begin_readback();
  /// Completes the oldest begun readback into `rgba` (bottom-up RGBA rows, resized; its old
  /// storage may be swapped in for reuse).
  void finish_readback(std::vector<std::uint8_t>& rgba);
  bool async_readback() const;
  /// The last drawn frame as a top-down RGB image.
  Image read_image();

  int width() const;
  int height() const;
  int msaa_samples() const;     ///< samples actually used (0 = none)
  Antialias antialias() const;  ///< the technique in use (msaa falls back to none if unsupported)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
