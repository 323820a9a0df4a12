#pragma once
/// A Scene is the parsed, validated, immutable description of one run: what the scene file says,
/// with every default made explicit. What a scene leaves out is not modelled (no floor: no
/// collision work; zero drag: no drag computed). Units are SI; angles are radians inside.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/integrators.hpp"
#include "tumble/math.hpp"
#include "tumble/mesh.hpp"

namespace tumble {

enum class Shape { Box, Particle, Mesh, Sphere };
/// Names of MeshRepair values in enum order, as a scene writes them.
inline constexpr std::array<std::string_view, 3> kMeshRepairNames = {"none", "orient", "hull"};
std::string_view to_string(Shape shape);

/// An sRGB colour, 8 bits per channel, as written "#rrggbb" in a scene.
struct Color {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Color&) const = default;
};
std::string to_string(Color c);  ///< "#rrggbb"

struct SimulationSettings {
  double duration_s = 4.0;
  double dt_s = 0.001;  ///< fixed physics step, independent of fps
  Integrator integrator = Integrator::Rk4;
  RotationRep rotation = RotationRep::Quaternion;
  double tolerance = 1e-8;  ///< adaptive only: local error tolerance
  /// adaptive only: the largest step, s (dt is then the first trial step). Absent: the interval
  /// between samples (render: 1/fps; simulate: 1/rate), so every sample is a step boundary.
  std::optional<double> max_step_s;
  Vec3 gravity{0.0, -9.81, 0.0};
  double linear_drag = 0.0;   ///< N·s/m; 0 = not modelled
  double angular_drag = 0.0;  ///< N·m·s; 0 = not modelled
  /// `collisions = "all"`: bodies meet each other as well as the floor; "floor": only the floor.
  bool collisions = true;
};

/// The plane y = height. Present only when the scene has a [floor] table.
struct FloorSettings {
  double height = 0.0;
  double restitution = 0.5;  ///< default for bodies that set none, in [0, 1]
  double friction = 0.0;     ///< Coulomb mu >= 0; 0 = frictionless
};

/// How edges are anti-aliased. FXAA is one cheap full-screen pass (the default: on a CPU
/// rasteriser 4x MSAA triples the cost of a frame); MSAA takes `msaa` samples per pixel.
enum class Antialias { Fxaa, Msaa, None };
inline constexpr std::array<std::string_view, 3> kAntialiasNames = {"fxaa", "msaa", "none"};

struct RenderSettings {
  int fps = 60;
  int width = 1280;
  int height = 720;
  Antialias antialias = Antialias::Fxaa;
  int msaa = 4;  ///< samples when antialias = msaa
  Color background{0xdf, 0xe6, 0xee};
};

/// How the camera maps the scene to the image: a perspective (a pinhole, things shrink with
/// distance) or an orthographic projection (parallel rays: sizes and heights read true at any
/// depth, the side view of textbook figures).
enum class Projection { Perspective, Orthographic };
inline constexpr std::array<std::string_view, 2> kProjectionNames = {"perspective", "orthographic"};

/// The direction a framed camera (no position in the scene) looks from, towards the scene: SPEC's
/// default camera position (camera_framing.hpp).
inline const Vec3 kFramingDirection{5.0, 3.0, 6.0};

struct CameraSettings {
  Vec3 position{5.0, 3.0, 6.0};
  Vec3 target{0.0, 0.5, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double fov_deg = 45.0;  ///< perspective only: vertical field of view
  Projection projection = Projection::Perspective;
  double ortho_height_m = 4.0;  ///< orthographic only: metres of the scene shown top to bottom
  std::optional<std::string> follow;  ///< name of a body to keep in view
  /// What the scene file states. No position: the camera frames the run (camera_framing.hpp).
  bool position_given = false, target_given = false, ortho_height_given = false;
  /// Set on the camera actually used when its position (and target, ortho height) came from
  /// framing the run rather than from the scene.
  bool framed = false;
};

struct LightSettings {
  Vec3 direction{-0.4, -1.0, -0.3};
  bool shadows = true;
};

struct BodySpec {
  std::string name;
  Shape shape = Shape::Box;
  Vec3 size{1.0, 1.0, 1.0};   ///< box: full edge lengths; particle: drawn size; sphere: 2r
  double radius_m = 0.0;      ///< sphere only
  std::string mesh;           ///< shape = mesh: path as resolved against the scene's folder
  SourceLocation mesh_where;  ///< where the scene names the mesh
  Vec3 scale = Vec3::Ones();  ///< mesh: file units -> metres, per axis
  MeshRepair repair = MeshRepair::None;
  std::optional<double> mass;     ///< kg; exactly one of mass and density is set
  std::optional<double> density;  ///< kg/m^3
  Vec3 position = Vec3::Zero();   ///< centre of mass, m
  Quat orientation = Quat::Identity();
  Vec3 velocity = Vec3::Zero();          ///< m/s
  Vec3 angular_velocity = Vec3::Zero();  ///< rad/s, world frame
  std::optional<double> restitution;     ///< overrides the floor's
  std::optional<double> friction;        ///< Coulomb mu; default: the floor's (0 without one)
  bool fixed = false;                    ///< does not move (ramps, tables, walls, pegs)
  Color color;
  bool color_given = false;  ///< `color` is in the file: it overrides a model's own materials
  SourceLocation where;  ///< the [[body]] header, for errors found after parsing
};

/// `[[pair]]`: what two named bodies (or a body and "floor") do when they meet.
struct PairSpec {
  int a = -1, b = -1;  ///< body indices, a < b; -1 = the floor
  std::optional<double> restitution, friction;
  bool collide = true;
  SourceLocation where;
};

struct Scene {
  std::string source_name;  ///< file path as given, or "<default>" for the built-in scene
  std::string source_text;  ///< the exact bytes parsed (hashed into run.json)
  std::string stem;         ///< file stem, "default" for the built-in scene: out/<stem>/
  SimulationSettings simulation;
  std::optional<FloorSettings> floor;
  RenderSettings render;
  CameraSettings camera;
  LightSettings light;
  std::vector<BodySpec> bodies;
  std::vector<PairSpec> pairs;  ///< sorted by (a, b)
};

/// Command-line values for the run's length and step: they replace the file's before the
/// file's dt <= duration check (the caller then checks the overridden pair).
struct TimeOverrides {
  std::optional<double> duration_s, dt_s;
};

/// Parses and validates scene text. `source_name` is used in error locations and to resolve
/// mesh paths. Throws tumble::Error (BadInput) with file:line:column on any problem.
Scene parse_scene(std::string_view text, const std::string& source_name,
                  const TimeOverrides& overrides = {});

/// Reads and parses a scene file. A file that cannot be read is BadInput (exit 2).
Scene load_scene_file(const std::filesystem::path& path, const TimeOverrides& overrides = {});

/// The seed's experiment: a box dropped with a tilt and a spin onto a floor.
Scene default_scene();

/// The closest of `candidates` to `word` when it is close enough to be a likely typo.
std::optional<std::string> closest_match(std::string_view word,
                                         const std::vector<std::string_view>& candidates);

}  // namespace tumble
