#include "tumble/renderer.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <optional>

#include "gl_resources.hpp"
#include "tumble/camera.hpp"
#include "tumble/error.hpp"
#include "tumble/premultiplied.hpp"

namespace tumble {
namespace {

using Mat4 = Eigen::Matrix4d;
using Mat4f = Eigen::Matrix4f;

Vec3 color_of(Color c) {
  return Vec3(c.r, c.g, c.b) / 255.0;
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// The floor is flat, so its lighting is one colour per tile, computed once here with the same
// hemisphere ambient + Lambert terms as shade() in common.glsl (normal straight up).
Vec3 floor_tile_color(const Vec3& albedo_srgb, const Vec3& light) {
  const double diffuse = std::max(-light.y(), 0.0);
  const Vec3 ambient(0.38, 0.42, 0.48);  // shade()'s sky colour, n.y = 1
  Vec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = linear_to_srgb(srgb_to_linear(albedo_srgb[i]) * (ambient[i] + 0.85 * diffuse));
  return out;
}

}  // namespace

struct Renderer::Impl {
  Scene scene;  // a copy: reuse_for() points a built renderer at the next scene
  const SceneModels* models;
  std::vector<Mesh> model_meshes;        // per body: its model's triangles (vao 0 for other shapes)
  std::vector<Vec3> model_lo, model_hi;  // per mesh body: its model's bounding box, model frame
  int width, height, samples = 0;
  Antialias antialias;
  Backdrop backdrop;
  GLuint mesh_program = 0, floor_program = 0, fxaa_program = 0;
  // Bodies that share a model, many in one draw (mesh_instanced.vert): one vertex array per
  // shared model (its vertices, and the instances' attributes pointed at per draw) and the
  // instances of the picture being drawn.
  GLuint instanced_program = 0, instance_vbo = 0;
  std::array<GLuint, 3> instanced_vao = {0, 0, 0};  // by SharedModel
  bool each_body = false;  // every body drawn on its own: the reference for instancing
  // FXAA's pixels: rectangles marked in the stencil (pixel_rects.vert), their corners streamed.
  GLuint rects_program = 0, rects_vao = 0, rects_vbo = 0;
  Mesh cube, sphere, ball, floor;
  GLuint empty_vao = 0;                           // the full-screen triangle needs no buffers
  // Models' textures are bound here; unit 0 is FXAA's.
  static constexpr GLint kModelTextureUnit = 1;
  double checker_m = 1.0;  // the side of the floor's squares, m (floor_tile_m)
  GLuint ms_fbo = 0, ms_color = 0, ms_depth = 0;  // multisampled target (msaa)
  GLuint tex_color = 0;  // where fxaa reads the scene from: its edge rectangles, copied
  GLuint fbo = 0, color = 0, depth = 0;  // single-sample target read back

  // Readback: pixel-pack buffers and fences (async), or buffers filled at once (sync); a ring of
  // two, oldest first.
  bool async = false;
  GLuint pbo[2] = {0, 0};
  GLsync fence[2] = {nullptr, nullptr};
  std::vector<std::uint8_t> sync_frame[2];
  int begun = 0, finished = 0;

  Impl(const Scene& s, const SceneModels* m, Backdrop b)
      : scene(s),
        models(m),
        width(s.render.width),
        height(s.render.height),
        antialias(s.render.antialias),
        backdrop(b) {}

  // The picture format the framebuffers and programs were built for (what the scene asked).
  bool same_format(const Scene& s, Backdrop b) const {
    return s.render.width == scene.render.width && s.render.height == scene.render.height &&
           s.render.antialias == scene.render.antialias && s.render.msaa == scene.render.msaa &&
           b == backdrop;
  }
  static bool has_meshes(const Scene& s) {
    return std::any_of(s.bodies.begin(), s.bodies.end(),
                       [](const BodySpec& b) { return b.shape == Shape::Mesh; });
  }

  ~Impl() {
    for (Mesh* m : {&cube, &sphere, &ball, &floor}) m->release();
    for (Mesh& m : model_meshes) m.release();
    glDeleteVertexArrays(1, &empty_vao);
    glDeleteVertexArrays(1, &rects_vao);
    glDeleteBuffers(1, &rects_vbo);
    glDeleteVertexArrays(GLsizei(instanced_vao.size()), instanced_vao.data());
    glDeleteBuffers(1, &instance_vbo);
    for (GLuint program :
         {mesh_program, floor_program, fxaa_program, rects_program, instanced_program})
      glDeleteProgram(program);
    const GLuint fbos[] = {ms_fbo, fbo};
    glDeleteFramebuffers(2, fbos);
    const GLuint rbs[] = {ms_color, ms_depth, color, depth};
    glDeleteRenderbuffers(4, rbs);
    glDeleteTextures(1, &tex_color);
    for (GLsync& f : fence)
      if (f) glDeleteSync(f);
    glDeleteBuffers(2, pbo);
  }

  // A framebuffer with n samples (0 = single), colour and depth-stencil in renderbuffers.
  void make_target(GLuint& target, GLuint& c, GLuint& d, int n) {
    glGenFramebuffers(1, &target);
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glGenRenderbuffers(1, &c);
    glBindRenderbuffer(GL_RENDERBUFFER, c);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c);
    glGenRenderbuffers(1, &d);
    glBindRenderbuffer(GL_RENDERBUFFER, d);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_DEPTH24_STENCIL8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, d);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      gl_fail("framebuffer " + std::to_string(width) + "x" + std::to_string(height) + " with " +
              std::to_string(n) + " samples is incomplete (status " + std::to_string(status) + ")");
  }

  void build() {
    GLint max_size = 0, max_samples = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (width > max_size || height > max_size)
      throw Error(ErrorKind::BadInput, "image size " + std::to_string(width) + "x" +
                                           std::to_string(height) +
                                           " exceeds this GPU's limit of " +
                                           std::to_string(max_size) + " pixels per side");
    // msaa 0 or 1 means none; more is clamped to the driver's limit (4 on llvmpipe).
    if (antialias == Antialias::Msaa && scene.render.msaa > 1)
      samples = std::min(scene.render.msaa, max_samples);
    if (antialias == Antialias::Msaa && samples <= 1) antialias = Antialias::None;
    if (samples > 0) make_target(ms_fbo, ms_color, ms_depth, samples);
    if (antialias == Antialias::Fxaa) {
      // The texture FXAA samples (linearly, along the edge it finds).
      glGenTextures(1, &tex_color);
      glBindTexture(GL_TEXTURE_2D, tex_color);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   nullptr);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      fxaa_program = link_program("fullscreen.vert", "fxaa.frag");
      glGenVertexArrays(1, &empty_vao);
      rects_program = link_program("pixel_rects.vert", "stencil_only.frag");
      glGenVertexArrays(1, &rects_vao);
      glGenBuffers(1, &rects_vbo);
      glBindVertexArray(rects_vao);
      glBindBuffer(GL_ARRAY_BUFFER, rects_vbo);
      glEnableVertexAttribArray(0);
      glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
      glBindVertexArray(0);
    }
    make_target(fbo, color, depth, 0);
    mesh_program = link_program("mesh.vert", "mesh.frag");
    glUseProgram(mesh_program);
    glUniform1i(glGetUniformLocation(mesh_program, "u_texture"), kModelTextureUnit);
    instanced_program = link_program("mesh_instanced.vert", "mesh.frag");
    glUseProgram(instanced_program);
    glUniform1i(glGetUniformLocation(instanced_program, "u_texture"), kModelTextureUnit);
    floor_program = link_program("floor.vert", "floor.frag");
    cube = make_cube();
    sphere = make_sphere();
    ball = make_marked_sphere();
    floor = make_floor_quad();
    // The shared models' vertices as their own arrays have them (position, normal: attributes
    // 0 and 1), with the instances' attributes beside them.
    glGenBuffers(1, &instance_vbo);
    glGenVertexArrays(GLsizei(instanced_vao.size()), instanced_vao.data());
    for (const SharedModel m : {SharedModel::Cube, SharedModel::Ball, SharedModel::Particle}) {
      const Mesh& mesh = shared_mesh(m);
      glBindVertexArray(instanced_vao[std::size_t(m)]);
      glBindBuffer(GL_ARRAY_BUFFER, mesh.vbo);
      glEnableVertexAttribArray(0);
      glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
      glEnableVertexAttribArray(1);
      glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                            reinterpret_cast<void*>(3 * sizeof(float)));
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.ebo);
      for (GLuint a = kFirstInstanceAttribute; a < kFirstInstanceAttribute + 8; ++a) {
        glEnableVertexAttribArray(a);
        glVertexAttribDivisor(a, 1);
      }
    }
    glBindVertexArray(0);
    checker_m = floor_tile_m(scene, models);
    // Each model is uploaded once; a frame only sets its transform.
    model_meshes.resize(scene.bodies.size());
    model_lo.assign(scene.bodies.size(), Vec3::Constant(-0.5));
    model_hi.assign(scene.bodies.size(), Vec3::Constant(0.5));
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].shape != Shape::Mesh) continue;
      const MeshBody* model = models ? models->model(i) : nullptr;
      if (!model) gl_fail("mesh body \"" + scene.bodies[i].name + "\" has no loaded model");
      // The model's own materials, unless the scene gives the body a colour.
      const BodySpec& spec = scene.bodies[i];
      const Vec3 body = color_of(spec.color);
      model_meshes[i] = make_model(
          model->mesh, spec.color_given ? nullptr : &model->appearance,
          Vec3(srgb_to_linear(body.x()), srgb_to_linear(body.y()), srgb_to_linear(body.z())));
      Vec3 lo = model->mesh.vertices.front(), hi = lo;
      for (const Vec3& p : model->mesh.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      model_lo[i] = lo;
      model_hi[i] = hi;
    }
    if (glGetError() != GL_NO_ERROR) gl_fail("setting up the renderer failed");
  }

  // The models bodies share: a box draws the unit cube, a sphere the marked ball, a particle the
  // plain sphere. A mesh body draws its own model, on its own (its materials are its own).
  enum class SharedModel { Cube, Ball, Particle };
  static std::optional<SharedModel> shared_model(Shape shape) {
    switch (shape) {
      case Shape::Box:
        return SharedModel::Cube;
      case Shape::Sphere:
        return SharedModel::Ball;
      case Shape::Particle:
        return SharedModel::Particle;
      case Shape::Mesh:
        break;
    }
    return std::nullopt;
  }
  const Mesh& shared_mesh(SharedModel m) const {
    return m == SharedModel::Cube ? cube : m == SharedModel::Ball ? ball : sphere;
  }

  // One body as mesh_instanced.vert reads it: the values draw_body() sets as uniforms, as the
  // same floats (the ball's marking colour beside its colour: the marked triangles are a second
  // draw with the colour attribute pointed there).
  struct Instance {
    float model[16];         // column-major, attributes 4-7
    float normal_matrix[9];  // column-major, attributes 8-10
    float color[3];          // sRGB, attribute 11
    float marking[3];        // the ball's marked octants' colour
  };
  static constexpr GLuint kFirstInstanceAttribute = 4;
  // Instances [first, first + count) of the picture's, all of one shared model.
  struct Run {
    std::size_t first = 0;
    GLsizei count = 0;
  };
  using Runs = std::array<Run, 3>;  // by SharedModel
  std::vector<Instance> instances;  // the picture's: the lit bodies', then each exposure's shadows
  Runs lit_runs;                    // the opaque exposures' bodies
  std::vector<Runs> shadow_runs;    // by exposure

  static Instance instance(const Mat4& model, const Mat3& normal_matrix, const Vec3& color,
                           const Vec3& marking) {
    Instance out;
    const Mat4f m = model.cast<float>();
    const Eigen::Matrix3f n = normal_matrix.cast<float>();
    std::copy_n(m.data(), 16, out.model);
    std::copy_n(n.data(), 9, out.normal_matrix);
    for (int k = 0; k < 3; ++k) {
      out.color[k] = float(color[k]);
      out.marking[k] = float(marking[k]);
    }
    return out;
  }
  static Vec3 marking_color(const Vec3& color) { return 0.5 * (color + Vec3::Ones()); }

  // The instances of a picture, uploaded once for all its scissored passes: every opaque
  // exposure's bodies by shared model (exposure, then scene order within each model: the order
  // draw_body() would draw them in), and each exposure's bodies flattened onto the floor.
  void prepare_instances(std::span<const Exposure> exposures, const Vec3& light, bool shadows) {
    instances.clear();
    lit_runs = Runs{};
    shadow_runs.assign(shadows ? exposures.size() : 0, Runs{});
    if (each_body) return;
    const auto add = [&](const World& world, SharedModel m, const Mat4* flatten) {
      for (std::size_t i = 0; i < world.bodies().size(); ++i) {
        if (shared_model(scene.bodies[i].shape) != m) continue;
        const Mat4 model = model_matrix(world, i);
        const Vec3 rgb = color_of(scene.bodies[i].color);
        instances.push_back(flatten ? instance(*flatten * model, Mat3::Identity(), rgb, rgb)
                                    : instance(model, model.block<3, 3>(0, 0).inverse().transpose(),
                                               rgb, marking_color(rgb)));
      }
    };
    for (const SharedModel m : {SharedModel::Cube, SharedModel::Ball, SharedModel::Particle}) {
      Run& run = lit_runs[std::size_t(m)];
      run.first = instances.size();
      for (const Exposure& e : exposures)
        if (e.opacity >= 1.0) add(*e.world, m, nullptr);
      run.count = GLsizei(instances.size() - run.first);
    }
    if (shadows) {
      const Mat4 flatten = flattening(light, scene.floor->height);
      for (std::size_t e = 0; e < exposures.size(); ++e)
        for (const SharedModel m : {SharedModel::Cube, SharedModel::Ball, SharedModel::Particle}) {
          Run& run = shadow_runs[e][std::size_t(m)];
          run.first = instances.size();
          add(*exposures[e].world, m, &flatten);
          run.count = GLsizei(instances.size() - run.first);
        }
    }
    glBindBuffer(GL_ARRAY_BUFFER, instance_vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(instances.size() * sizeof(Instance)), instances.data(),
                 GL_STREAM_DRAW);
  }

  // The run's instances of model m with the instanced program current: indices [first,
  // first + count) of the model, in the instances' colour or (the ball's marking) their marking.
  void draw_instances(SharedModel m, const Run& run, GLsizei first_index, GLsizei index_count,
                      bool marking) {
    if (run.count == 0) return;
    glBindVertexArray(instanced_vao[std::size_t(m)]);
    glBindBuffer(GL_ARRAY_BUFFER, instance_vbo);
    const std::size_t base = run.first * sizeof(Instance);
    const auto point = [&](GLuint a, GLint size, std::size_t offset) {
      glVertexAttribPointer(a, size, GL_FLOAT, GL_FALSE, GLsizei(sizeof(Instance)),
                            reinterpret_cast<const void*>(base + offset));
    };
    for (GLuint c = 0; c < 4; ++c)
      point(kFirstInstanceAttribute + c, 4, offsetof(Instance, model) + 4 * c * sizeof(float));
    for (GLuint c = 0; c < 3; ++c)
      point(kFirstInstanceAttribute + 4 + c, 3,
            offsetof(Instance, normal_matrix) + 3 * c * sizeof(float));
    point(kFirstInstanceAttribute + 7, 3,
          marking ? offsetof(Instance, marking) : offsetof(Instance, color));
    glDrawElementsInstanced(
        GL_TRIANGLES, index_count, GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(sizeof(unsigned) * std::size_t(first_index)), run.count);
  }
  // Every instance of the runs, whole models (shadows) or lit (the ball in its two colours).
  void draw_runs(const Runs& runs, bool lit) {
    draw_instances(SharedModel::Cube, runs[0], 0, cube.count, false);
    if (lit) {
      draw_instances(SharedModel::Ball, runs[1], ball.marked, ball.count - ball.marked, false);
      draw_instances(SharedModel::Ball, runs[1], 0, ball.marked, true);
    } else {
      draw_instances(SharedModel::Ball, runs[1], 0, ball.count, false);
    }
    draw_instances(SharedModel::Particle, runs[2], 0, sphere.count, false);
  }
  // Whether body i is drawn on its own (with draw_body, draw_mesh) rather than as an instance.
  bool on_its_own(std::size_t i) const { return each_body || !shared_model(scene.bodies[i].shape); }

  static void set(GLuint program, const char* name, const Mat4& m) {
    const Mat4f f = m.cast<float>();
    glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, f.data());
  }
  static void set(GLuint program, const char* name, const Mat3& m) {
    const Eigen::Matrix3f f = m.cast<float>();
    glUniformMatrix3fv(glGetUniformLocation(program, name), 1, GL_FALSE, f.data());
  }
  static void set(GLuint program, const char* name, const Vec3& v) {
    glUniform3f(glGetUniformLocation(program, name), float(v.x()), float(v.y()), float(v.z()));
  }
  static void set(GLuint program, const char* name, double x) {
    glUniform1f(glGetUniformLocation(program, name), float(x));
  }

  static void set(GLuint program, const char* name, const Eigen::Vector4d& v) {
    glUniform4f(glGetUniformLocation(program, name), float(v.x()), float(v.y()), float(v.z()),
                float(v.w()));
  }

  bool transparent() const { return backdrop == Backdrop::Transparent; }

  // Where the viewer is, for the specular term: a point (w = 1) for a perspective camera, a
  // direction towards it (w = 0) for an orthographic one, whose rays are all parallel.
  Eigen::Vector4d eye(const World& world) const {
    const CameraSettings& cam = scene.camera;
    if (cam.projection == Projection::Orthographic) {
      const Vec3 d = (camera_eye(scene, world) - camera_target(scene, world)).normalized();
      return {d.x(), d.y(), d.z(), 0.0};
    }
    const Vec3 at = camera_eye(scene, world);  // moves with a followed body
    return {at.x(), at.y(), at.z(), 1.0};
  }

  // Where the floor fades away. A perspective camera sees it shrink towards a horizon: it fades
  // 12-40 squares around what the camera looks at (12-40 m with 1 m squares), farther for a
  // camera farther away (1.2 and 4 times its distance, so a framed 50 m throw keeps its ground;
  // a camera within 10 squares gets 12-40 squares). A floor of the bodies' scale: past 40
  // squares a square is a few pixels at most, and the filtered checker is an even grey.
  // An orthographic camera sees it at one scale however deep, so a
  // floor there would fill the picture below the horizon with tiles flattened into stripes: it
  // is a band along the view's depth instead, full within 0.3 ortho_height of what the camera
  // looks at and gone at 1 ortho_height, the ground line of a textbook side view. (Looking
  // straight down there is no depth along the floor: the perspective rule.)
  struct FloorFade {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero(), axis = Eigen::Vector2d::Zero();
    double start_m = 12.0, end_m = 40.0;
  };
  FloorFade floor_fade(const World& world) const {
    const CameraSettings& cam = scene.camera;
    FloorFade f;
    f.start_m *= checker_m;
    f.end_m *= checker_m;
    const Vec3 target = camera_target(scene, world);
    const Vec3 view = target - camera_eye(scene, world);
    if (cam.projection != Projection::Orthographic) {
      f.centre = Eigen::Vector2d(target.x(), target.z());
      f.start_m = std::max(f.start_m, 1.2 * view.norm());
      f.end_m = std::max(f.end_m, 4.0 * view.norm());
      // Gone before the far plane (camera.cpp: 200 m + 4 distances) could cut it off: a floor
      // point at end_m from the target is at most distance + end_m from the eye.
      f.end_m = std::min(f.end_m, 200.0 + 3.0 * view.norm());
      f.start_m = std::min(f.start_m, 0.3 * f.end_m);
      return f;
    }
    const Eigen::Vector2d along(view.x(), view.z());
    if (along.norm() < 1e-3 * view.norm()) return f;
    f.centre = Eigen::Vector2d(target.x(), target.z());
    f.axis = along.normalized();
    f.start_m = 0.3 * cam.ortho_height_m;
    f.end_m = cam.ortho_height_m;
    return f;
  }

  using Rect = Eigen::Array4i;  // pixels x0, y0, x1, y1 (GL's bottom-up rows), half-open

  // What the last picture was drawn with, for redrawing only what changed since (see draw()).
  struct Drawn {
    Mat4 view_projection;
    FloorFade fade;
    std::vector<Rect> rects;  // where its bodies and their shadows lie (edge_rects)
  };
  std::optional<Drawn> drawn;  // empty: the framebuffer holds no picture to build on
  bool full_redraw = false;    // every picture from scratch (the reference; tests compare)
  double redrawn = 0.0;        // the share of the frame the last draw() drew

  Rect whole() const { return {0, 0, width, height}; }

  // The rectangles whose pixels differ between the last picture and the next one, merged so
  // that none overlap and there are few (each is one pass over the scene): the whole frame when
  // the camera or the floor moved, or when there is no last picture.
  std::vector<Rect> dirty_rects(const Mat4& view_projection, const FloorFade& fade,
                                const std::vector<Rect>& now) const {
    if (full_redraw || !drawn || drawn->view_projection != view_projection ||
        drawn->fade.centre != fade.centre || drawn->fade.axis != fade.axis ||
        drawn->fade.start_m != fade.start_m || drawn->fade.end_m != fade.end_m)
      return {whole()};
    std::vector<Rect> rects = drawn->rects;
    rects.insert(rects.end(), now.begin(), now.end());
    return few_covering(std::move(rects));
  }

  static Rect bounding_box(const std::vector<Rect>& all) {
    Rect box = all.front();
    for (const Rect& r : all)
      box = Rect(std::min(box[0], r[0]), std::min(box[1], r[1]), std::max(box[2], r[2]),
                 std::max(box[3], r[3]));
    return box;
  }

  // At most 8 rectangles, none overlapping, that cover `rects` (non-empty), for work that costs
  // a pass per rectangle and may cover more pixels than asked.
  static std::vector<Rect> few_covering(std::vector<Rect> rects) {
    // Many bodies: one box around them all (a pass per rectangle draws every body, and merging
    // many rectangles pairwise would cost more than it saves).
    constexpr std::size_t kMaxPasses = 8, kMaxMerged = 64;
    if (rects.size() > kMaxMerged) return {bounding_box(rects)};
    // Overlapping (or touching) rectangles become their bounding box, until none overlap.
    for (bool merged = true; merged;) {
      merged = false;
      for (std::size_t i = 0; i < rects.size() && !merged; ++i)
        for (std::size_t j = i + 1; j < rects.size() && !merged; ++j) {
          const Rect &a = rects[i], &b = rects[j];
          if (a[0] > b[2] || b[0] > a[2] || a[1] > b[3] || b[1] > a[3]) continue;
          rects[i] = Rect(std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[2], b[2]),
                          std::max(a[3], b[3]));
          rects.erase(rects.begin() + std::ptrdiff_t(j));
          merged = true;
        }
    }
    if (rects.size() > kMaxPasses) return {bounding_box(rects)};
    return rects;
  }

  // Rectangles that cover exactly the pixels of `rects` and none twice: the union cut into
  // horizontal bands at every rectangle's top and bottom, each band's covered runs of x merged,
  // and a run continued downwards while the next band has it too. For work whose pixels must be
  // exactly those asked, once each (FXAA: a thousand bodies' overlapping rectangles cost a
  // thousand passes over mostly the same pixels).
  static std::vector<Rect> disjoint_union(std::vector<Rect> rects) {
    std::sort(rects.begin(), rects.end(), [](const Rect& a, const Rect& b) { return a[0] < b[0]; });
    std::vector<int> ys;
    for (const Rect& r : rects) ys.insert(ys.end(), {r[1], r[3]});
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    std::vector<Rect> out;
    std::vector<std::size_t> open, next;  // runs of the last band (indices into out), left to right
    for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
      const int y0 = ys[k], y1 = ys[k + 1];
      next.clear();
      std::size_t o = 0;  // the last band's runs are in x order too: one merge-like walk
      for (std::size_t i = 0; i < rects.size();) {
        if (rects[i][1] > y0 || rects[i][3] < y1) {
          ++i;
          continue;
        }
        // A run of x: this rectangle and every later one in the band that overlaps or touches.
        int x0 = rects[i][0], x1 = rects[i][2];
        for (++i; i < rects.size() && rects[i][0] <= x1; ++i)
          if (rects[i][1] <= y0 && rects[i][3] >= y1) x1 = std::max(x1, rects[i][2]);
        while (o < open.size() && out[open[o]][0] < x0) ++o;
        if (o < open.size() && out[open[o]][0] == x0 && out[open[o]][2] == x1 &&
            out[open[o]][3] == y0) {
          out[open[o]][3] = y1;  // the same run continues from the band above
          next.push_back(open[o]);
        } else {
          out.emplace_back(x0, y0, x1, y1);
          next.push_back(out.size() - 1);
        }
      }
      open.swap(next);
    }
    return out;
  }

  // Draws a picture. When the camera and the floor are where they were for the last picture,
  // only the pixels that can differ are drawn again: the rectangles of the bodies and shadows
  // of both pictures. Everywhere else the last picture is the floor and sky this one would draw
  // (FXAA changed only pixels inside its rectangles, which are redrawn). Each rectangle is
  // cleared and drawn in full under a scissor, and OpenGL's invariance rules make a fragment's
  // value independent of the scissor rectangle, so the picture is the same bytes as a full
  // redraw (tested against full_redraw, the reference).
  void draw(std::span<const Exposure> exposures) {
    assert(!exposures.empty());
    // The camera maths live in camera.cpp, so `tumble study` measures pixels of this picture.
    // Several exposures are seen from where the camera is at the last (camera.follow).
    const World& last = *exposures.back().world;
    const Mat4 view_projection = camera_view_projection(scene, last);
    const Vec3 light = scene.light.direction.normalized();
    const FloorFade fade = floor_fade(last);
    std::vector<Rect> rects = edge_rects(exposures, view_projection, light);
    const std::vector<Rect> dirty = dirty_rects(view_projection, fade, rects);
    redrawn = 0.0;
    for (const Rect& r : dirty) redrawn += double(r[2] - r[0]) * double(r[3] - r[1]);
    redrawn /= double(width) * double(height);

    prepare_instances(exposures, light, casts_shadows(light));
    glBindFramebuffer(GL_FRAMEBUFFER, antialias == Antialias::Msaa ? ms_fbo : fbo);
    glViewport(0, 0, width, height);
    glEnable(GL_SCISSOR_TEST);
    for (const Rect& r : dirty) {
      glScissor(r[0], r[1], r[2] - r[0], r[3] - r[1]);
      draw_scene(exposures, view_projection, light, fade);
    }
    glDisable(GL_SCISSOR_TEST);
    drawn = Drawn{view_projection, fade, rects};

    if (antialias == Antialias::Msaa) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
      glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    } else if (antialias == Antialias::Fxaa) {
      if (!rects.empty()) smooth_edges(rects);
    }
  }

  // The floor and the background have no geometric edges (the checker is filtered in its
  // shader, the horizon fades), so FXAA runs only inside the screen rectangles of the bodies
  // and their shadows, in place: the rectangles, grown by what FXAA reads around a pixel, are
  // copied into the texture it samples (rectangles that cover them: copying more changes
  // nothing), and FXAA writes over exactly the rectangles' pixels of the frame, each once: they
  // are marked in the stencil, and one full-screen triangle is drawn where the stencil is set.
  // A full-screen pass or copy costs ~5-30 ms at 720p on llvmpipe, against ~1 ms for these.
  void smooth_edges(const std::vector<Rect>& rects) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex_color);
    // Every copy before any FXAA write: overlapping rectangles all read the unsmoothed scene.
    std::vector<Rect> reach;
    for (const Rect& r : rects) reach.push_back(grown(r, kFxaaReach));
    for (const Rect& c : few_covering(std::move(reach)))
      glCopyTexSubImage2D(GL_TEXTURE_2D, 0, c[0], c[1], c[0], c[1], c[2] - c[0], c[3] - c[1]);
    glDisable(GL_DEPTH_TEST);
    // The rectangles' pixels, once each, into the stencil (cleared around them first: the
    // scene's shadows left their counts there).
    std::vector<float> corners;
    for (const Rect& r : disjoint_union(rects)) {
      const float x0 = float(r[0]), y0 = float(r[1]), x1 = float(r[2]), y1 = float(r[3]);
      corners.insert(corners.end(), {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1});
    }
    const Rect box = bounding_box(rects);
    glEnable(GL_SCISSOR_TEST);
    glScissor(box[0], box[1], box[2] - box[0], box[3] - box[1]);
    glClearStencil(0);
    glClear(GL_STENCIL_BUFFER_BIT);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(rects_program);
    glUniform2f(glGetUniformLocation(rects_program, "u_pixel"), 1.0f / float(width),
                1.0f / float(height));
    glBindVertexArray(rects_vao);
    glBindBuffer(GL_ARRAY_BUFFER, rects_vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners.size() * sizeof(float)), corners.data(),
                 GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(corners.size() / 2));
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // FXAA where the stencil is set: the same triangle, so the same values, as one per rectangle.
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glUseProgram(fxaa_program);
    glUniform1i(glGetUniformLocation(fxaa_program, "u_image"), 0);
    glUniform2f(glGetUniformLocation(fxaa_program, "u_pixel"), 1.0f / float(width),
                1.0f / float(height));
    glUniform1i(glGetUniformLocation(fxaa_program, "u_alpha"), transparent() ? 1 : 0);
    glBindVertexArray(empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
  }

  // The scene (sky, floor, shadows, bodies) into the bound framebuffer, inside the scissor.
  void draw_scene(std::span<const Exposure> exposures, const Mat4& view_projection,
                  const Vec3& light, const FloorFade& f) {
    const Vec3 bg = color_of(scene.render.background);
    // Transparent: premultiplied (0, 0, 0, 0) behind everything, whatever the sky's colour.
    if (transparent())
      glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    else
      glClearColor(float(bg.x()), float(bg.y()), float(bg.z()), 1.0f);
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);

    if (scene.floor) {
      const double h = scene.floor->height;
      // Floor: a square around the fade's centre, big enough to reach the fade-out.
      const double extent = std::max(60.0 * checker_m, 1.5 * f.end_m);
      Mat4 model = Mat4::Identity();
      model(0, 0) = model(2, 2) = extent;
      model(0, 3) = f.centre.x();
      model(2, 3) = f.centre.y();
      model(1, 3) = h;
      glUseProgram(floor_program);
      set(floor_program, "u_model", model);
      set(floor_program, "u_view_projection", view_projection);
      set(floor_program, "u_tile_light", floor_tile_color(Vec3(0.80, 0.82, 0.85), light));
      set(floor_program, "u_tile_dark", floor_tile_color(Vec3(0.68, 0.71, 0.75), light));
      set(floor_program, "u_background", bg);
      glUniform1i(glGetUniformLocation(floor_program, "u_transparent"), transparent() ? 1 : 0);
      glUniform2f(glGetUniformLocation(floor_program, "u_fade_centre"), float(f.centre.x()),
                  float(f.centre.y()));
      glUniform2f(glGetUniformLocation(floor_program, "u_fade_axis"), float(f.axis.x()),
                  float(f.axis.y()));
      set(floor_program, "u_fade_start", f.start_m);
      set(floor_program, "u_fade_end", f.end_m);
      set(floor_program, "u_checker_m", checker_m);
      glBindVertexArray(floor.vao);
      glDrawElements(GL_TRIANGLES, floor.count, GL_UNSIGNED_INT, nullptr);
      if (casts_shadows(light)) draw_shadows(exposures, view_projection, light, h);
    }

    // Opaque bodies first, writing depth: those that share a model as instances, the others
    // one by one; then the translucent ones over them.
    for (const GLuint program : {instanced_program, mesh_program}) {
      glUseProgram(program);
      set(program, "u_view_projection", view_projection);
      set(program, "u_light_direction", light);
      set(program, "u_eye", eye(*exposures.back().world));
      set(program, "u_shadow", 0.0);
      set(program, "u_opacity", 1.0);
      glUniform1i(glGetUniformLocation(program, "u_material"), 0);
    }
    glUseProgram(instanced_program);
    draw_runs(lit_runs, true);
    glUseProgram(mesh_program);
    for (const Exposure& e : exposures)
      if (e.opacity >= 1.0)
        for (std::size_t i = 0; i < e.world->bodies().size(); ++i)
          if (on_its_own(i)) draw_body(*e.world, i);
    draw_translucent(exposures, view_projection);
  }

  bool casts_shadows(const Vec3& light) const {
    return scene.floor && scene.light.shadows && light.y() < -1e-3;
  }

  // Body i of `world`, lit, with the mesh program's current opacity and blend state.
  void draw_body(const World& world, std::size_t i) {
    const Mat4 model = model_matrix(world, i);
    set(mesh_program, "u_model", model);
    set(mesh_program, "u_normal_matrix", Mat3(model.block<3, 3>(0, 0).inverse().transpose()));
    set(mesh_program, "u_color", color_of(scene.bodies[i].color));
    if (scene.bodies[i].shape == Shape::Sphere) {
      // The marking: every other octant in the body's colour lightened halfway to white.
      glBindVertexArray(ball.vao);
      glDrawElements(GL_TRIANGLES, ball.count - ball.marked, GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(sizeof(unsigned) * std::size_t(ball.marked)));
      set(mesh_program, "u_color", marking_color(color_of(scene.bodies[i].color)));
      glDrawElements(GL_TRIANGLES, ball.marked, GL_UNSIGNED_INT, nullptr);
      return;
    }
    const Mesh& mesh = model_meshes[i];
    if (scene.bodies[i].shape == Shape::Mesh && !mesh.parts.empty()) {
      // In its own materials: a run of indices per material, each with its texture or none.
      glUniform1i(glGetUniformLocation(mesh_program, "u_material"), 1);
      glBindVertexArray(mesh.vao);
      glActiveTexture(GL_TEXTURE0 + kModelTextureUnit);
      for (const MeshPart& part : mesh.parts) {
        glBindTexture(GL_TEXTURE_2D, part.texture);
        glUniform1i(glGetUniformLocation(mesh_program, "u_textured"), part.texture != 0 ? 1 : 0);
        glDrawElements(GL_TRIANGLES, part.count, GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(sizeof(unsigned) * std::size_t(part.first)));
      }
      glBindTexture(GL_TEXTURE_2D, 0);
      glActiveTexture(GL_TEXTURE0);
      glUniform1i(glGetUniformLocation(mesh_program, "u_material"), 0);
      return;
    }
    draw_mesh(i);
  }

  // The translucent bodies of every exposure, far to near by the depth of their centres, each
  // blended (premultiplied "over") where it is the nearest surface: a depth-only pass first, so
  // a ghost shows its front and not its back faces too (which a concave mesh would).
  void draw_translucent(std::span<const Exposure> exposures, const Mat4& view_projection) {
    struct Ghost {
      double depth;
      std::size_t exposure, body;
    };
    std::vector<Ghost> ghosts;
    for (std::size_t e = 0; e < exposures.size(); ++e) {
      if (exposures[e].opacity >= 1.0) continue;
      const World& w = *exposures[e].world;
      for (std::size_t i = 0; i < w.bodies().size(); ++i) {
        const Eigen::Vector4d clip = view_projection * w.bodies()[i].state.x.homogeneous();
        // NDC depth: monotonic in distance for both projections (w > 0 in front of the eye).
        ghosts.push_back({clip.z() / std::max(clip.w(), 1e-9), e, i});
      }
    }
    if (ghosts.empty()) return;
    // Stable: equal depths keep exposure then body order, so the picture is deterministic.
    std::stable_sort(ghosts.begin(), ghosts.end(),
                     [](const Ghost& a, const Ghost& b) { return a.depth > b.depth; });
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied colours, alpha too
    for (const Ghost& g : ghosts) {
      const World& w = *exposures[g.exposure].world;
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glDepthFunc(GL_LESS);
      draw_body(w, g.body);
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glDepthFunc(GL_LEQUAL);
      glDepthMask(GL_FALSE);
      set(mesh_program, "u_opacity", std::clamp(exposures[g.exposure].opacity, 0.0, 1.0));
      draw_body(w, g.body);
      set(mesh_program, "u_opacity", 1.0);
      glDepthMask(GL_TRUE);
    }
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
  }

  // How far around a pixel FXAA reads (fxaa.frag): its four diagonal neighbours, and linear
  // samples at most 4 px away along the edge (the step is clamped to 8 px, sampled at ±1/2 of
  // it), whose 2×2 footprints reach one texel further; one more for safety.
  static constexpr int kFxaaReach = 6;

  // Rectangle r grown by n pixels on every side, clipped to the frame.
  Eigen::Array4i grown(const Rect& r, int n) const {
    return {std::max(r[0] - n, 0), std::max(r[1] - n, 0), std::min(r[2] + n, width),
            std::min(r[3] + n, height)};
  }

  // Pixel rectangles (x0, y0, x1, y1; GL's bottom-up rows) that hold every edge of body i and
  // of its shadow: the projected corners of its bounding box, flattened onto the floor too,
  // grown by the FXAA reach. A corner behind the camera makes it the whole screen.
  std::vector<Rect> edge_rects(std::span<const Exposure> exposures, const Mat4& view_projection,
                               const Vec3& light) const {
    std::vector<Rect> rects;
    for (const Exposure& e : exposures) {
      std::vector<Rect> more = edge_rects(*e.world, view_projection, light);
      // A body behind the camera: the whole screen, once.
      if (more.size() == 1 && (more[0] == Eigen::Array4i(0, 0, width, height)).all()) return more;
      rects.insert(rects.end(), more.begin(), more.end());
    }
    return rects;
  }

  std::vector<Rect> edge_rects(const World& world, const Mat4& view_projection,
                               const Vec3& light) const {
    std::vector<Rect> rects;
    const bool shadows = scene.floor && scene.light.shadows && light.y() < -1e-3;
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      const Mat4 model = model_matrix(world, i);
      Eigen::Array2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
      bool behind = false;
      const Vec3 &blo = model_lo[i], &bhi = model_hi[i];  // box, particle: the unit cube
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? bhi.x() : blo.x(), (c & 2) ? bhi.y() : blo.y(),
                          (c & 4) ? bhi.z() : blo.z());
        Vec3 world_corner = (model * corner.homogeneous()).head<3>();
        for (int pass = 0; pass < (shadows ? 2 : 1); ++pass) {
          if (pass == 1)  // the same corner flattened onto the floor along the light
            world_corner -= ((world_corner.y() - scene.floor->height) / light.y()) * light;
          const Eigen::Vector4d clip = view_projection * world_corner.homogeneous();
          if (clip.w() <= 1e-6) {
            behind = true;
            continue;
          }
          const Eigen::Array2d ndc = clip.head<2>().array() / clip.w();
          const Eigen::Array2d px = (ndc + 1.0) * 0.5 * Eigen::Array2d(width, height);
          lo = lo.min(px);
          hi = hi.max(px);
        }
      }
      if (behind) return {Eigen::Array4i(0, 0, width, height)};
      // FXAA reads one pixel around and blends up to 8 pixels along an edge.
      const int x0 = std::clamp(int(std::floor(lo.x())) - 10, 0, width);
      const int y0 = std::clamp(int(std::floor(lo.y())) - 10, 0, height);
      const int x1 = std::clamp(int(std::ceil(hi.x())) + 10, 0, width);
      const int y1 = std::clamp(int(std::ceil(hi.y())) + 10, 0, height);
      if (x1 > x0 && y1 > y0) rects.emplace_back(x0, y0, x1, y1);
    }
    return rects;
  }

  Mat4 model_matrix(const World& world, std::size_t i) const {
    const RigidBody& b = world.bodies()[i];
    const BodyState& s = b.state;
    Mat4 m = Mat4::Identity();
    if (scene.bodies[i].shape == Shape::Mesh) {
      // The model's triangles are in its file's frame: rotate by the model's orientation and
      // put its centre of mass (com_offset in that frame) at the body's position.
      const Mat3 R = b.model_orientation().toRotationMatrix();
      m.block<3, 3>(0, 0) = R;
      m.block<3, 1>(0, 3) = s.x - R * b.com_offset();
      return m;
    }
    m.block<3, 3>(0, 0) = s.R * scene.bodies[i].size.asDiagonal();
    m.block<3, 1>(0, 3) = s.x;
    return m;
  }

  void draw_mesh(std::size_t i) {
    const Shape shape = scene.bodies[i].shape;
    const Mesh& mesh = shape == Shape::Mesh       ? model_meshes[i]
                       : shape == Shape::Sphere   ? ball
                       : shape == Shape::Particle ? sphere
                                                  : cube;
    glBindVertexArray(mesh.vao);
    glDrawElements(GL_TRIANGLES, mesh.count, GL_UNSIGNED_INT, nullptr);
  }

  // Flattens points onto the plane y = h along the light: p' = p − ((p_y − h) / L_y) L, as a
  // matrix acting on homogeneous points.
  static Mat4 flattening(const Vec3& light, double h) {
    Mat4 flatten = Mat4::Identity();
    flatten.block<3, 1>(0, 1) -= light / light.y();
    flatten.block<3, 1>(0, 3) += light * (h / light.y());
    return flatten;
  }

  // Planar shadows: each body flattened onto the plane y = h along the light, darkening the
  // floor under it. The stencil lets each pixel darken once where shadows overlap (a box's front
  // and back faces land on the same pixels, and so do the shadows of strobe poses that overlap).
  // The exposures are drawn most opaque first, so a pixel takes the darkest shadow over it: a
  // pile of faint poses never blackens the floor. Exact for a plane, one cheap extra pass.
  void draw_shadows(std::span<const Exposure> exposures, const Mat4& view_projection,
                    const Vec3& light, double h) {
    const Mat4 flatten = flattening(light, h);
    glUseProgram(instanced_program);
    set(instanced_program, "u_view_projection", view_projection);
    glUseProgram(mesh_program);
    set(mesh_program, "u_view_projection", view_projection);
    set(mesh_program, "u_normal_matrix", Mat3(Mat3::Identity()));
    glDisable(GL_DEPTH_TEST);  // on the floor nothing but bodies (drawn later) can cover them
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    // dst · (1 − s), alpha kept: a shadow darkens the floor that is there and is as transparent
    // as the floor (with a transparent backdrop, the floor's fade takes its shadow along).
    glBlendFuncSeparate(GL_ZERO, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    std::vector<std::size_t> order(exposures.size());
    for (std::size_t e = 0; e < order.size(); ++e) order[e] = e;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return exposures[a].opacity > exposures[b].opacity;
    });
    for (const std::size_t e : order) {
      // One exposure's shadows are all alike: drawn in any order, a pixel darkens the same.
      const double shadow = 0.32 * std::clamp(exposures[e].opacity, 0.0, 1.0);
      if (!each_body) {
        glUseProgram(instanced_program);
        set(instanced_program, "u_shadow", shadow);
        draw_runs(shadow_runs[e], false);
        glUseProgram(mesh_program);
      }
      set(mesh_program, "u_shadow", shadow);
      const World& world = *exposures[e].world;
      for (std::size_t i = 0; i < world.bodies().size(); ++i) {
        if (!on_its_own(i)) continue;
        set(mesh_program, "u_model", Mat4(flatten * model_matrix(world, i)));
        draw_mesh(i);
      }
    }
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glEnable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
  }

  void setup_readback(Readback mode) {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string name = renderer ? renderer : "";
    const bool cpu_rasteriser = name.find("llvmpipe") != std::string::npos ||
                                name.find("softpipe") != std::string::npos ||
                                name.find("SwiftShader") != std::string::npos;
    async = mode == Readback::Async || (mode == Readback::Auto && !cpu_rasteriser);
    if (!async) return;
    glGenBuffers(2, pbo);
    for (GLuint b : pbo) {
      glBindBuffer(GL_PIXEL_PACK_BUFFER, b);
      glBufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(width) * height * 4, nullptr, GL_STREAM_READ);
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (glGetError() != GL_NO_ERROR) gl_fail("creating the readback buffers failed");
  }

  void begin_readback() {
    if (begun - finished >= 2) gl_fail("more than two readbacks in flight");  // a caller bug
    const int slot = begun % 2;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (async) {
      glBindBuffer(GL_PIXEL_PACK_BUFFER, pbo[slot]);
      glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
      glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
      fence[slot] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
      glFlush();  // so the copy starts now, not at the next wait
    } else {
      read_rgba(sync_frame[slot]);
    }
    if (glGetError() != GL_NO_ERROR) gl_fail("starting a readback failed");
    ++begun;
  }

  void finish_readback(std::vector<std::uint8_t>& out) {
    if (finished >= begun) gl_fail("no readback in flight");  // a caller bug
    const int slot = finished % 2;
    ++finished;
    if (!async) {
      std::swap(out, sync_frame[slot]);  // no copy: the caller's old buffer is reused next time
      return;
    }
    glClientWaitSync(fence[slot], GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(10'000'000'000));
    glDeleteSync(fence[slot]);
    fence[slot] = nullptr;
    out.resize(std::size_t(width) * height * 4);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pbo[slot]);
    const void* mapped =
        glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(out.size()), GL_MAP_READ_BIT);
    if (!mapped) gl_fail("mapping a readback buffer failed");
    std::memcpy(out.data(), mapped, out.size());
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  }

  void read_rgba(std::vector<std::uint8_t>& out) {
    out.resize(std::size_t(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, out.data());
    if (glGetError() != GL_NO_ERROR) gl_fail("reading the frame back failed");
  }
};

Renderer::Renderer(const Scene& scene, Readback readback, const SceneModels* models,
                   Backdrop backdrop)
    : impl_(std::make_unique<Impl>(scene, models, backdrop)) {
  impl_->build();
  impl_->setup_readback(readback);
}
bool Renderer::reuse_for(const Scene& scene, const SceneModels* models, Backdrop backdrop) {
  Impl& m = *impl_;
  // Mesh bodies have their models uploaded per scene; a readback still in flight belongs to
  // the old scene's frame.
  if (!m.same_format(scene, backdrop) || Impl::has_meshes(scene) || Impl::has_meshes(m.scene) ||
      m.begun != m.finished)
    return false;
  m.scene = scene;
  m.models = models;
  m.drawn.reset();  // the next picture is drawn in full
  // No mesh bodies: every body draws the shared cube or sphere (empty model entries).
  m.model_meshes.assign(scene.bodies.size(), Mesh{});
  m.model_lo.assign(scene.bodies.size(), Vec3::Constant(-0.5));
  m.model_hi.assign(scene.bodies.size(), Vec3::Constant(0.5));
  m.checker_m = floor_tile_m(scene, models);
  return true;
}
void Renderer::begin_readback() {
  impl_->begin_readback();
}
void Renderer::finish_readback(std::vector<std::uint8_t>& rgba) {
  impl_->finish_readback(rgba);
}
bool Renderer::async_readback() const {
  return impl_->async;
}
Renderer::~Renderer() = default;
void Renderer::draw(const World& world) {
  const Exposure one{&world, 1.0};
  impl_->draw(std::span<const Exposure>(&one, 1));
}
void Renderer::draw(std::span<const Exposure> exposures) {
  impl_->draw(exposures);
}
void Renderer::redraw_in_full(bool on) {
  impl_->full_redraw = on;
}
void Renderer::draw_each_body(bool on) {
  impl_->each_body = on;
}
double Renderer::redrawn_share() const {
  return impl_->redrawn;
}
void Renderer::read_rgba(std::vector<std::uint8_t>& rgba) {
  impl_->read_rgba(rgba);
}
int Renderer::width() const {
  return impl_->width;
}
int Renderer::height() const {
  return impl_->height;
}
int Renderer::msaa_samples() const {
  return impl_->samples;
}
Antialias Renderer::antialias() const {
  return impl_->antialias;
}
Backdrop Renderer::backdrop() const {
  return impl_->backdrop;
}

Image Renderer::read_image() {
  std::vector<std::uint8_t> rgba;
  read_rgba(rgba);
  return backdrop() == Backdrop::Transparent
             ? straight_image_from_gl_rgba(rgba.data(), width(), height())
             : image_from_gl_rgba(rgba.data(), width(), height());
}

}  // namespace tumble
