#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <span>
#include <system_error>
#include <tuple>

#include "table_reader.hpp"
#include "tumble/scene.hpp"

namespace tumble {
namespace {

// The tables a scene may have, in the order the documentation lists them.
constexpr std::array<std::string_view, 7> kTableNames = {
    "simulation", "floor", "render", "camera", "light", "body", "pair"};
constexpr std::array<std::string_view, 2> kCollisionNames = {"all", "floor"};

// Colours of bodies that name none, by body order; the first is the seed's orange box.
constexpr std::array<Color, 6> kPalette = {Color{0xd9, 0x57, 0x2b}, Color{0x2b, 0x7b, 0xd9},
                                           Color{0x3f, 0xa3, 0x4d}, Color{0xd9, 0xb3, 0x2b},
                                           Color{0x8e, 0x44, 0xad}, Color{0x16, 0xa0, 0x85}};

using namespace scene_toml;  // fail, location, TableReader, Bounds, ...

// The length of v, robust to overflow and underflow (0 only for the zero vector).
double length(const Vec3& v) {
  return v.stableNorm();
}

SimulationSettings read_simulation(const toml::table& table, const std::string& file,
                                   const TimeOverrides& overrides) {
  const TableReader r(table, "[simulation]", file,
                      {"duration", "dt", "integrator", "tolerance", "max_step", "rotation",
                       "gravity", "linear_drag", "angular_drag", "collisions"});
  SimulationSettings s;
  // The upper bound (about 11.6 days) keeps the step and frame counts of a run sane.
  s.duration_s = r.number("duration", {0.0, 1e6, true, false}).value_or(s.duration_s);
  s.dt_s = r.number("dt", kPositive).value_or(s.dt_s);
  // Command-line values replace the file's before the cross-check: --duration or --dt may be
  // exactly what makes a scene's pair valid. The caller checks the overridden pair itself.
  if (overrides.duration_s || overrides.dt_s) {
    s.duration_s = overrides.duration_s.value_or(s.duration_s);
    s.dt_s = overrides.dt_s.value_or(s.dt_s);
  } else if (s.dt_s > s.duration_s)
    fail(r.where(r.has("dt") ? "dt" : "duration"), "dt in [simulation] (" + format_number(s.dt_s) +
                                                       " s) must not exceed duration (" +
                                                       format_number(s.duration_s) + " s)");
  if (const auto i = r.choice("integrator", kIntegratorNames))
    s.integrator = static_cast<Integrator>(*i);  // kIntegratorNames is in enum order
  // Below 1e-14 a local error is round-off, not truncation; above 0.1 nothing is controlled.
  s.tolerance = r.number("tolerance", {1e-14, 0.1, false, false}).value_or(s.tolerance);
  // Like tolerance, read (and checked) whatever the integrator, used by adaptive alone: a scene
  // keeps it while --integrator tries a fixed-step method.
  s.max_step_s = r.number("max_step", kPositive);
  if (const auto i = r.choice("rotation", kRotationNames))
    s.rotation = static_cast<RotationRep>(*i);
  s.gravity = r.vec3("gravity").value_or(s.gravity);
  s.linear_drag = r.number("linear_drag", kNonNegative).value_or(s.linear_drag);
  s.angular_drag = r.number("angular_drag", kNonNegative).value_or(s.angular_drag);
  if (const auto i = r.choice("collisions", kCollisionNames)) s.collisions = *i == 0;
  return s;
}

FloorSettings read_floor(const toml::table& table, const std::string& file) {
  const TableReader r(table, "[floor]", file, {"height", "restitution", "friction"});
  FloorSettings f;
  f.height = r.number("height").value_or(f.height);
  f.restitution = r.number("restitution", kUnitInterval).value_or(f.restitution);
  f.friction = r.number("friction", kNonNegative).value_or(f.friction);
  return f;
}

RenderSettings read_render(const toml::table& table, const std::string& file) {
  const TableReader r(table, "[render]", file,
                      {"fps", "width", "height", "antialias", "msaa", "background"});
  RenderSettings s;
  s.fps = r.integer("fps", 1, 1000).value_or(s.fps);
  // 16384 is the smallest GL_MAX_RENDERBUFFER_SIZE that GL 4.x allows a driver to offer.
  s.width = r.integer("width", 1, 16384).value_or(s.width);
  s.height = r.integer("height", 1, 16384).value_or(s.height);
  // Samples per pixel, 0 = off. What a driver offers is known only at render time (llvmpipe:
  // up to 4), so this checks only for plausibility.
  s.msaa = r.integer("msaa", 0, 16).value_or(s.msaa);
  // msaa is the sample count used when antialias = "msaa" (SPEC); alone it changes nothing.
  if (const auto i = r.choice("antialias", kAntialiasNames))
    s.antialias = static_cast<Antialias>(*i);  // kAntialiasNames is in enum order
  s.background = r.color("background").value_or(s.background);
  return s;
}

CameraSettings read_camera(const toml::table& table, const std::string& file,
                           const std::vector<BodySpec>& bodies) {
  const TableReader r(
      table, "[camera]", file,
      {"position", "target", "up", "fov_deg", "projection", "ortho_height", "follow"});
  CameraSettings c;
  c.position_given = r.has("position");
  c.target_given = r.has("target");
  c.ortho_height_given = r.has("ortho_height");
  c.position = r.vec3("position").value_or(c.position);
  c.target = r.vec3("target").value_or(c.target);
  c.up = r.vec3("up").value_or(c.up);
  c.fov_deg = r.number("fov_deg", {0.0, 180.0, true, true}).value_or(c.fov_deg);
  if (const auto i = r.choice("projection", kProjectionNames))
    c.projection = static_cast<Projection>(*i);  // kProjectionNames is in enum order
  c.ortho_height_m = r.number("ortho_height", kPositive).value_or(c.ortho_height_m);
  // Each projection uses its own size key and ignores the other's (both still checked): SPEC's
  // [camera] table gives fov_deg and ortho_height together, so a scene may keep both and switch
  // the projection alone.

  // Blame the first of these keys the file gives: it is what the user wrote.
  const auto blame = [&](std::initializer_list<std::string_view> keys) {
    for (const std::string_view key : keys)
      if (r.has(key)) return r.where(key);
    return r.where();
  };
  // Without a stated position the camera frames the run, looking along -kFramingDirection.
  const Vec3 view = c.position_given ? Vec3(c.target - c.position) : Vec3(-kFramingDirection);
  if (length(view) == 0.0)
    fail(blame({"target", "position"}), "target in [camera] must differ from position");
  // A look-at builds its right vector from up x view; when the two are within about 1e-6 rad of
  // parallel that vector is mostly round-off and the image spins unpredictably. Written so that
  // a NaN (a zero up, or a view so long it overflows) fails the test too.
  const double sine = length((c.up / length(c.up)).cross(view / length(view)));
  if (!(sine >= 1e-6))
    fail(blame({"up", "target", "position"}),
         "up in [camera] must be non-zero and not parallel to the view direction "
         "(target - position)");

  c.follow = r.string("follow");
  if (c.follow) {
    std::vector<std::string_view> names;
    for (const BodySpec& body : bodies) names.push_back(body.name);
    if (std::find(names.begin(), names.end(), *c.follow) == names.end())
      fail(r.where("follow"), "follow in [camera] names no body: " + in_quotes(*c.follow) +
                                  suggestion(*c.follow, names));
  }
  return c;
}

LightSettings read_light(const toml::table& table, const std::string& file) {
  const TableReader r(table, "[light]", file, {"direction", "shadows"});
  LightSettings l;
  l.direction = r.vec3("direction").value_or(l.direction);
  if (length(l.direction) == 0.0)
    fail(r.where("direction"), "direction in [light] must be non-zero");
  l.shadows = r.boolean("shadows").value_or(l.shadows);
  return l;
}

// `orientation = { axis = [x, y, z], degrees = d }`: a rotation of d degrees about axis.
Quat read_orientation(const toml::table& table, const std::string& file) {
  const TableReader r(table, "[[body]] orientation", file, {"axis", "degrees"});
  r.require("axis", "a direction [x, y, z], any length but zero");
  r.require("degrees", "the angle of rotation about axis");
  const Vec3 axis = *r.vec3("axis");
  const double axis_length = length(axis);
  if (axis_length == 0.0) fail(r.where("axis"), "axis in [[body]] orientation must be non-zero");
  const double degrees = *r.number("degrees");
  return Quat(Eigen::AngleAxisd(radians(degrees), axis / axis_length));
}

// `number` is the body's 1-based place in the file; it picks the default name and colour.
BodySpec read_body(const toml::table& table, std::size_t number, const std::string& file) {
  const TableReader r(
      table, "[[body]]", file,
      {"name", "shape", "size", "radius", "mass", "density", "position", "orientation",
       "velocity", "angular_velocity", "restitution", "friction", "fixed", "color", "mesh",
       "scale", "repair"});
  BodySpec b;
  b.where = r.where();
  b.name = r.string("name").value_or("body" + std::to_string(number));
  if (b.name.empty()) fail(r.where("name"), "name in [[body]] must not be empty");

  std::vector<std::string_view> shape_names;
  // In the order SPEC lists them; Shape's enum order differs (sphere came later).
  const std::array<Shape, 4> shapes = {Shape::Box, Shape::Sphere, Shape::Particle, Shape::Mesh};
  for (const Shape shape : shapes) shape_names.push_back(to_string(shape));
  r.require("shape", "expected one of: " + join(shape_names));
  b.shape = shapes[*r.choice("shape", shape_names)];
  b.fixed = r.boolean("fixed").value_or(false);
  // Range-checked before their place, so a bad value is named before a misplaced key.
  b.scale = r.number_or_vec3("scale", kPositive).value_or(b.scale);
  const std::optional<std::size_t> repair = r.choice("repair", kMeshRepairNames);
  if (b.shape == Shape::Mesh) {
    r.require("mesh", "the model file, relative to the scene (OBJ, STL, PLY, glTF, ...)");
    const std::string path = *r.string("mesh");
    if (path.empty()) fail(r.where("mesh"), "mesh in [[body]] must name a file");
    // Relative to the scene file's folder, so a scene and its models move together.
    const std::filesystem::path p(path);
    b.mesh = (p.is_absolute() ? p : std::filesystem::path(file).parent_path() / p).string();
    b.mesh_where = r.where("mesh");
    if (repair) b.repair = static_cast<MeshRepair>(*repair);  // kMeshRepairNames in enum order
    r.forbid("size", "does not apply to a mesh: the model gives its size (use scale)");
  } else {
    r.forbid("mesh", "applies only to shape = \"mesh\"");
    r.forbid("scale", "applies only to shape = \"mesh\"");
    r.forbid("repair", "applies only to shape = \"mesh\"");
  }

  if (b.shape == Shape::Sphere) {
    r.require("radius", "a sphere needs its radius, m");
    r.forbid("size", "does not apply to a sphere: give its radius");
    b.radius_m = *r.number("radius", kPositive);
    b.size = Vec3::Constant(2.0 * b.radius_m);
  } else {
    r.forbid("radius", "applies only to shape = \"sphere\"");
  }
  if (b.shape == Shape::Box) r.require("size", "a box needs its full edge lengths [x, y, z], m");
  // A particle has no extent to simulate; its size is only how big it is drawn, m.
  if (b.shape == Shape::Particle) b.size = Vec3::Constant(0.1);
  b.size = r.vec3("size", kPositive).value_or(b.size);

  if (b.fixed) {
    // A fixed body does not move: it has no mass to give and no motion to start with.
    if (b.shape == Shape::Particle)
      fail(r.where("fixed"), "fixed in [[body]] does not apply to a particle: a fixed point "
                             "meets nothing (use a small sphere or box)");
    r.forbid("mass", "does not apply to a fixed body: it does not move");
    r.forbid("density", "does not apply to a fixed body: it does not move");
    r.forbid("velocity", "does not apply to a fixed body: it does not move");
    r.forbid("angular_velocity", "does not apply to a fixed body: it does not move");
    b.mass = 1.0;  // unused: a fixed body's inverse mass is zero
  } else {
    b.mass = r.number("mass", kPositive);
    b.density = r.number("density", kPositive);
    if (b.shape == Shape::Particle)
      r.forbid("density", "does not apply to a particle: it has no volume, give its mass");
    if (b.mass && b.density) fail(r.where("density"), "give mass or density in [[body]], not both");
    if (!b.mass && !b.density)
      fail(r.where(), "missing key \"mass\" or \"density\" in [[body]] (kg or kg/m^3)");
  }

  b.position = r.vec3("position").value_or(b.position);
  b.velocity = r.vec3("velocity").value_or(b.velocity);
  // A particle carries no rotation state, so these would be silently dropped.
  if (b.shape == Shape::Particle) {
    r.forbid("orientation", "does not apply to a particle: it has no orientation");
    r.forbid("angular_velocity", "does not apply to a particle: it does not rotate");
  }
  if (const toml::table* o = r.table("orientation", "{ axis = [x, y, z], degrees = d }"))
    b.orientation = read_orientation(*o, file);
  b.angular_velocity = r.vec3("angular_velocity").value_or(b.angular_velocity);
  b.restitution = r.number("restitution", kUnitInterval);
  b.friction = r.number("friction", kNonNegative);
  const std::optional<Color> color = r.color("color");
  b.color_given = color.has_value();
  b.color = color.value_or(kPalette[(number - 1) % kPalette.size()]);
  return b;
}

std::vector<BodySpec> read_bodies(const toml::table& root, const std::string& file) {
  const toml::node* node = root.get("body");
  if (!node) fail({file}, "a scene needs at least one [[body]]");
  const toml::array* array = node->as_array();
  if (!array)
    fail(location(*node, file),
         "body must be an array of tables, written [[body]], got " + std::string(type_name(*node)));
  if (array->empty()) fail(location(*node, file), "a scene needs at least one [[body]]");

  std::vector<BodySpec> bodies;
  for (const toml::node& element : *array) {
    const toml::table* table = element.as_table();
    if (!table)
      fail(location(element, file),
           "each body must be a table, written [[body]], got " + std::string(type_name(element)));
    BodySpec body = read_body(*table, bodies.size() + 1, file);
    for (const BodySpec& other : bodies) {
      if (other.name != body.name) continue;
      const toml::node* name = table->get("name");
      fail(name ? location(*name, file) : body.where,
           "duplicate body name " + in_quotes(body.name) + " (first used by the [[body]] on line " +
               std::to_string(other.where.line) + ")" +
               (name ? "" : "; this [[body]] has no name and was given that default: name it"));
    }
    bodies.push_back(std::move(body));
  }
  return bodies;
}

// `[[pair]]` entries: two body names (or "floor"), each pair once.
std::vector<PairSpec> read_pairs(const toml::table& root, const std::string& file,
                                 const std::vector<BodySpec>& bodies) {
  std::vector<PairSpec> pairs;
  const toml::node* node = root.get("pair");
  if (!node) return pairs;
  const toml::array* array = node->as_array();
  if (!array)
    fail(location(*node, file),
         "pair must be an array of tables, written [[pair]], got " + std::string(type_name(*node)));
  std::vector<std::string_view> names = {"floor"};
  for (const BodySpec& b : bodies) names.push_back(b.name);
  for (const toml::node& element : *array) {
    const toml::table* table = element.as_table();
    if (!table)
      fail(location(element, file),
           "each pair must be a table, written [[pair]], got " + std::string(type_name(element)));
    const TableReader r(*table, "[[pair]]", file, {"bodies", "restitution", "friction", "collide"});
    PairSpec p;
    p.where = r.where();
    r.require("bodies", "the two bodies' names, or a body and \"floor\": [\"a\", \"b\"]");
    const toml::array* list = table->get("bodies")->as_array();
    if (!list || list->size() != 2 || !(*list)[0].is_string() || !(*list)[1].is_string())
      fail(r.where("bodies"), "bodies in [[pair]] must be two names, like [\"ball\", \"ramp\"]");
    int index[2];
    for (int k = 0; k < 2; ++k) {
      const std::string& name = (*list)[static_cast<std::size_t>(k)].as_string()->get();
      const auto it = std::find(names.begin(), names.end(), name);
      if (it == names.end())
        fail(location((*list)[static_cast<std::size_t>(k)], file),
             "bodies in [[pair]] names no body: " + in_quotes(name) + suggestion(name, names));
      index[k] = static_cast<int>(it - names.begin()) - 1;  // "floor" is -1
    }
    if (index[0] == index[1])
      fail(r.where("bodies"), "bodies in [[pair]] names " +
                                  in_quotes(names[static_cast<std::size_t>(index[0] + 1)]) +
                                  " twice: a pair is two different bodies");
    p.a = std::min(index[0], index[1]);
    p.b = std::max(index[0], index[1]);
    p.restitution = r.number("restitution", kUnitInterval);
    p.friction = r.number("friction", kNonNegative);
    p.collide = r.boolean("collide").value_or(true);
    for (const PairSpec& q : pairs)
      if (q.a == p.a && q.b == p.b)
        fail(r.where("bodies"), "this pair of bodies is already given a [[pair]] on line " +
                                    std::to_string(q.where.line));
    pairs.push_back(p);
  }
  std::sort(pairs.begin(), pairs.end(), [](const PairSpec& x, const PairSpec& y) {
    return std::pair(x.a, x.b) < std::pair(y.a, y.b);
  });
  return pairs;
}

// A top-level table such as [render], or null when the file has none.
const toml::table* section(const toml::table& root, std::string_view name,
                           const std::string& file) {
  const toml::node* node = root.get(name);
  if (!node) return nullptr;
  if (!node->is_table())
    fail(location(*node, file),
         "[" + std::string(name) + "] must be a table, got " + std::string(type_name(*node)));
  return node->as_table();
}

void reject_unknown_tables(const toml::table& root, const std::string& file) {
  const toml::key* key = first_unknown_key(root, kTableNames);
  if (!key) return;
  const toml::node& node = *root.get(key->str());
  const std::string what = node.is_array_of_tables() ? "table [[" + std::string(key->str()) + "]]"
                           : node.is_table()         ? "table [" + std::string(key->str()) + "]"
                                                     : "top-level key " + in_quotes(key->str());
  fail(location(key->source().begin, file),
       "unknown " + what + suggestion(key->str(), kTableNames));
}

toml::table parse_toml(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    // toml++ words its errors "Error while parsing <part>: <problem>"; the CLI already says
    // "error:", so say what kind of error instead.
    constexpr std::string_view kPrefix = "Error while parsing ";
    std::string_view description = e.description();
    const bool has_prefix = description.starts_with(kPrefix);
    if (has_prefix) description.remove_prefix(kPrefix.size());
    fail(location(e.source().begin, file),
         std::string(has_prefix ? "TOML syntax error in " : "TOML syntax error: ") +
             std::string(description));
  }
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source_name,
                  const TimeOverrides& overrides) {
  const toml::table root = parse_toml(text, source_name);
  reject_unknown_tables(root, source_name);

  Scene scene;
  scene.source_name = source_name;
  scene.source_text = std::string(text);
  scene.stem = std::filesystem::path(source_name).stem().string();
  if (const toml::table* t = section(root, "simulation", source_name))
    scene.simulation = read_simulation(*t, source_name, overrides);
  if (const toml::table* t = section(root, "floor", source_name))
    scene.floor = read_floor(*t, source_name);
  if (const toml::table* t = section(root, "render", source_name))
    scene.render = read_render(*t, source_name);
  // Bodies before the camera: `follow` must name one of them.
  scene.bodies = read_bodies(root, source_name);
  scene.pairs = read_pairs(root, source_name, scene.bodies);
  if (const toml::table* t = section(root, "camera", source_name))
    scene.camera = read_camera(*t, source_name, scene.bodies);
  if (const toml::table* t = section(root, "light", source_name))
    scene.light = read_light(*t, source_name);
  return scene;
}

Scene load_scene_file(const std::filesystem::path& path, const TimeOverrides& overrides) {
  const auto cannot_read = [&](const std::string& reason) {
    fail({}, "cannot read scene file " + in_quotes(path.string()) + ": " + reason);
  };
  // Opening a directory succeeds on Linux and only the read fails; say what is wrong up front.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) cannot_read("it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) cannot_read(errno ? std::generic_category().message(errno) : "cannot open it");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) cannot_read("read failed");
  return parse_scene(text, path.string(), overrides);
}

}  // namespace tumble
