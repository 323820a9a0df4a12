#pragma once
/// Draws a World into an off-screen framebuffer and reads the pixels back. Needs a current
/// OpenGL 3.3 core context (EglContext). The look: scene colours (a mesh body in its model's own
/// materials and textures where its file has them and the scene gives it no colour), a checker
/// floor (checker_tile_m) that fades
/// into the background, Blinn-Phong lighting from [light], planar shadows of the bodies on the
/// floor (exact for a plane and one extra cheap pass, instead of a shadow map), FXAA or MSAA,
/// sRGB output. The camera is the scene's (perspective or orthographic, camera.hpp).
///
/// A picture may hold several exposures of the bodies (a stroboscopic figure): every pose with
/// its shadow, the translucent ones blended back to front over the opaque ones, in one pass.
/// With a transparent backdrop the background is alpha 0, the floor fades into transparency
/// instead of into the sky, and shadows, translucent poses and anti-aliased edges carry alpha.
///
/// Only what changed is drawn: while the camera and the floor stay where they were for the
/// last picture, a picture is drawn (under a scissor) only inside the screen rectangles of the
/// bodies and shadows of the last picture and this one; the rest of the framebuffer already
/// holds it. OpenGL's invariance rules make that the same bytes as a full redraw.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tumble/camera.hpp"  // look_at, perspective: the camera maths the renderer uses
#include "tumble/image.hpp"
#include "tumble/scene.hpp"
#include "tumble/world.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {

/// The side of the floor's checker squares, m: the power of ten nearest (in log scale) the size of
/// the largest moving body (its largest extent: a box's longest edge, a sphere's diameter, a
/// mesh's longest bounding-box side), so a 1 cm box stands on 1 cm squares and a 100 m one on
/// 100 m squares. Fixed bodies (a large ramp) and particles (whose drawn size is only a marker)
/// do not set it; without any other body it is 1 m.
double checker_tile_m(const Scene& scene, const SceneModels* models = nullptr);

/// The squares the renderer draws: checker_tile_m, times ten as often as needed (at most three
/// times) for a square on the floor below the camera's target to span at least 4 pixels along
/// both floor axes in the scene's picture, since smaller squares cannot be drawn without moiré
/// (an orthographic camera 8° above the floor, as in a side view, compresses depth sevenfold).
/// The floor's fade distances scale with it.
double floor_tile_m(const Scene& scene, const SceneModels* models = nullptr);

/// One exposure of a picture: the bodies as they are in `world`, drawn with `opacity` in (0, 1]
/// (1: opaque, as in a frame of the clip; less: translucent, as the earlier poses of a strobe).
/// Its shadow is drawn with the same share of the shadow's darkness.
struct Exposure {
  const World* world = nullptr;
  double opacity = 1.0;
};

/// What lies behind the scene. Sky: the scene's background colour, every pixel opaque.
/// Transparent: alpha 0 behind everything; frames come back as premultiplied RGBA
/// (premultiplied.hpp turns them into straight alpha, or composites them over a colour).
enum class Backdrop { Sky, Transparent };

class Renderer {
 public:
  /// How frames come back to the CPU. Async reads into pixel-pack buffers and collects them a
  /// frame later, so a GPU renders the next frame while the copy runs; on a CPU rasteriser
  /// (llvmpipe) the copy happens at once anyway and Sync saves a memcpy. Auto picks by renderer.
  enum class Readback { Auto, Sync, Async };

  /// Compiles the embedded shaders and builds the framebuffers for scene.render's size and
  /// msaa (clamped to what the driver offers). Throws tumble::Error (Environment) on GL failure.
  /// `models`: the loaded mesh of each mesh body (uploaded once); may be null for a scene
  /// without meshes.
  explicit Renderer(const Scene& scene, Readback readback = Readback::Auto,
                    const SceneModels* models = nullptr, Backdrop backdrop = Backdrop::Sky);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Points this renderer at another scene drawn in the same format (size, antialias, msaa,
  /// backdrop), keeping its shaders, framebuffers and buffers: a sweep's jobs one after another.
  /// Returns false and changes nothing when the format differs, when either scene has mesh
  /// bodies (their models are uploaded per scene), or while a readback is in flight; then build
  /// a new Renderer. Afterwards it draws exactly what a new Renderer for `scene` would.
  bool reuse_for(const Scene& scene, const SceneModels* models = nullptr,
                 Backdrop backdrop = Backdrop::Sky);

  /// Renders the bodies of `world` (in scene order) as they are now.
  void draw(const World& world);
  /// Renders several exposures into one picture (at least one), seen by the camera of the last
  /// one (camera.follow). Each exposure's shadow darkens the floor once; translucent bodies are
  /// sorted back to front by their centres and each shows only its nearest surface.
  void draw(std::span<const Exposure> exposures);
  /// A picture is drawn in full only where it can differ from the last one: while the camera
  /// and the floor stay put, the rectangles of the bodies and their shadows in both (the same
  /// bytes as drawing it all). `true`: every picture from scratch, the reference that claim is
  /// tested against.
  void redraw_in_full(bool on);
  /// Bodies that share a model (boxes, spheres, particles) are drawn many in one call, each
  /// with its own transform and colour (instancing), in the lit and the shadow pass; mesh bodies
  /// and translucent poses one by one. `true`: every body with its own draw call, the reference
  /// the instancing is tested against (the same bytes).
  void draw_each_body(bool on);
  /// The share of the frame's pixels the last draw() drew, in (0, 1].
  double redrawn_share() const;
  /// Reads the last drawn frame into `rgba` (resized) as RGBA rows, bottom-up as OpenGL returns
  /// them: straight into the caller's buffer, no copy. Premultiplied alpha (Transparent), or
  /// alpha 255 everywhere (Sky).
  void read_rgba(std::vector<std::uint8_t>& rgba);
  /// Starts reading the last drawn frame back; at most two may be in flight. Drawing may go on.
  void begin_readback();
  /// Completes the oldest begun readback into `rgba` (bottom-up RGBA rows, resized; its old
  /// storage may be swapped in for reuse).
  void finish_readback(std::vector<std::uint8_t>& rgba);
  bool async_readback() const;
  /// The last drawn frame as a top-down image: RGB (Sky), or straight-alpha RGBA (Transparent).
  Image read_image();

  int width() const;
  int height() const;
  int msaa_samples() const;     ///< samples actually used (0 = none)
  Antialias antialias() const;  ///< the technique in use (msaa falls back to none if unsupported)
  Backdrop backdrop() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
