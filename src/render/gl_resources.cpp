#include "gl_resources.hpp"

#include <algorithm>
#include <cmath>

#include "shader_sources.hpp"
#include "tumble/error.hpp"
#include "tumble/math.hpp"

namespace tumble {

[[noreturn]] void gl_fail(const std::string& what) {
  throw Error(ErrorKind::Environment, "OpenGL: " + what);
}

namespace {

GLuint compile(GLenum kind, const std::string& source, const char* name) {
  const GLuint shader = glCreateShader(kind);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    gl_fail(std::string("shader ") + name + " does not compile: " + log);
  }
  return shader;
}

}  // namespace

// Fragment shaders are assembled as: version line, shared lighting code, the shader itself.
GLuint link_program(const char* vert_name, const char* frag_name) {
  const GLuint vs = compile(GL_VERTEX_SHADER, std::string(shader_source(vert_name)), vert_name);
  const std::string frag = "#version 330 core\n" + std::string(shader_source("common.glsl")) +
                           std::string(shader_source(frag_name));
  const GLuint fs = compile(GL_FRAGMENT_SHADER, frag, frag_name);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) gl_fail(std::string("program ") + vert_name + "+" + frag_name + " does not link");
  return program;
}

namespace {

// A vertex array with its vertex and index buffers filled, left bound for the attributes.
Mesh upload_buffers(const std::vector<float>& vertices, const std::vector<unsigned>& indices) {
  Mesh m;
  glGenVertexArrays(1, &m.vao);
  glGenBuffers(1, &m.vbo);
  glGenBuffers(1, &m.ebo);
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(unsigned)),
               indices.data(), GL_STATIC_DRAW);
  m.count = static_cast<GLsizei>(indices.size());
  return m;
}

// Interleaved position + normal, indexed triangles.
Mesh upload(const std::vector<float>& vertices, const std::vector<unsigned>& indices) {
  Mesh m = upload_buffers(vertices, indices);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<void*>(3 * sizeof(float)));
  glBindVertexArray(0);
  return m;
}

// Interleaved position, normal, linear albedo, texture coordinates (11 floats), indexed.
Mesh upload_with_materials(const std::vector<float>& vertices,
                           const std::vector<unsigned>& indices) {
  Mesh m = upload_buffers(vertices, indices);
  constexpr GLsizei stride = 11 * sizeof(float);
  const GLint sizes[4] = {3, 3, 3, 2};
  std::size_t offset = 0;
  for (GLuint a = 0; a < 4; ++a) {
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(offset * sizeof(float)));
    offset += std::size_t(sizes[a]);
  }
  glBindVertexArray(0);
  return m;
}

// A texture as the shader samples it: sRGB-encoded texels decoded to linear by the sampler,
// mipmapped (a textured face far away neither shimmers nor aliases), repeating as glTF's
// default sampler and OBJ do. GL's first row is v = 0, the image's last.
GLuint upload_texture(const TextureImage& image) {
  std::vector<std::uint8_t> rows(image.rgba.size());
  const std::size_t stride = std::size_t(image.width) * 4;
  for (int y = 0; y < image.height; ++y)
    std::copy_n(image.rgba.begin() + std::ptrdiff_t(std::size_t(image.height - 1 - y) * stride),
                stride, rows.begin() + std::ptrdiff_t(std::size_t(y) * stride));
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (image.width > max_size || image.height > max_size)
    gl_fail("texture " + image.source + " of " + std::to_string(image.width) + "x" +
            std::to_string(image.height) + " exceeds this GPU's limit of " +
            std::to_string(max_size) + " pixels per side");
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, image.width, image.height, 0, GL_RGBA,
               GL_UNSIGNED_BYTE, rows.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

}  // namespace

void Mesh::release() {
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(1, &vbo);
  glDeleteBuffers(1, &ebo);
  if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
  textures.clear();
  parts.clear();
  vao = vbo = ebo = 0;
}

// Unit cube [-0.5, 0.5]³ with flat face normals: 24 vertices, 36 indices.
Mesh make_cube() {
  std::vector<float> v;
  std::vector<unsigned> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      Vec3 n = Vec3::Zero();
      n[axis] = sign;
      const Vec3 u = Vec3::Unit((axis + 1) % 3), w = Vec3::Unit((axis + 2) % 3);
      const unsigned base = static_cast<unsigned>(v.size() / 6);
      const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        const Vec3 p = 0.5 * (n + c[0] * u + c[1] * w);
        for (double x : {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()}) v.push_back(float(x));
      }
      // Counter-clockwise seen from outside: u × w = n for sign +1, so flip for sign −1.
      if (sign > 0)
        idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      else
        idx.insert(idx.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  return upload(v, idx);
}

// Unit-diameter UV sphere for particles.
Mesh make_sphere(int rings, int segments) {
  std::vector<float> v;
  std::vector<unsigned> idx;
  for (int r = 0; r <= rings; ++r) {
    const double theta = kPi * r / rings;
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2.0 * kPi * s / segments;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi));
      for (double x : {0.5 * n.x(), 0.5 * n.y(), 0.5 * n.z(), n.x(), n.y(), n.z()})
        v.push_back(float(x));
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const unsigned a = unsigned(r * (segments + 1) + s), b = a + unsigned(segments + 1);
      idx.insert(idx.end(), {a, a + 1, b, b, a + 1, b + 1});
    }
  return upload(v, idx);
}

Mesh make_marked_sphere(int rings, int segments) {
  // Rings and segments multiples of 2 and 4 put triangle edges on the three coordinate planes,
  // so every triangle lies in one octant; its centre's octant decides its colour.
  std::vector<float> v;
  std::vector<unsigned> marked, plain;
  auto point = [&](int r, int s) {
    const double theta = kPi * r / rings, phi = 2.0 * kPi * s / segments;
    return Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const Vec3 n = point(r, s);
      for (double x : {0.5 * n.x(), 0.5 * n.y(), 0.5 * n.z(), n.x(), n.y(), n.z()})
        v.push_back(float(x));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const unsigned a = unsigned(r * (segments + 1) + s), b = a + unsigned(segments + 1);
      // The cell's centre direction (not a vertex: off every coordinate plane).
      const double theta = kPi * (r + 0.5) / rings, phi = 2.0 * kPi * (s + 0.5) / segments;
      const Vec3 m(std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi));
      auto& to = m.x() * m.y() * m.z() > 0.0 ? marked : plain;
      to.insert(to.end(), {a, a + 1, b, b, a + 1, b + 1});
    }
  const GLsizei count = static_cast<GLsizei>(marked.size());
  marked.insert(marked.end(), plain.begin(), plain.end());
  Mesh mesh = upload(v, marked);
  mesh.marked = count;
  return mesh;
}

Mesh make_model(const TriangleMesh& mesh, const MeshAppearance* look,
                const Vec3& body_color_linear) {
  if (look != nullptr && !look->has_materials()) look = nullptr;
  const std::size_t nt = mesh.triangles.size();
  std::vector<Vec3> face_normal(nt);  // area-weighted (length = 2 × area)
  std::vector<std::vector<std::uint32_t>> faces_of(mesh.vertices.size());
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    face_normal[t] = (b - a).cross(c - a);
    for (std::uint32_t v : tri) faces_of[v].push_back(static_cast<std::uint32_t>(t));
  }
  const double crease_cos = std::cos(radians(40.0));
  // With materials, the triangles in material order (stable), one part per material.
  std::vector<std::size_t> order(nt);
  for (std::size_t t = 0; t < nt; ++t) order[t] = t;
  if (look != nullptr)
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return look->triangle_material[a] < look->triangle_material[b];
    });
  std::vector<float> v;
  v.reserve(nt * (look ? 33 : 18));
  std::vector<unsigned> idx;
  idx.reserve(nt * 3);
  Mesh out_parts;
  std::uint32_t current = UINT32_MAX;  // the material of the part being filled
  for (const std::size_t t : order) {
    const Vec3 own = face_normal[t].normalized();
    const MeshMaterial* material = nullptr;
    if (look != nullptr) {
      const std::uint32_t m = look->triangle_material[t];
      material = &look->materials[m];
      if (m != current)
        out_parts.parts.push_back({GLsizei(idx.size()), 0, GLuint(material->texture + 1)});
      current = m;
      out_parts.parts.back().count += 3;
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t corner = mesh.triangles[t][k];
      Vec3 n = Vec3::Zero();
      for (std::uint32_t f : faces_of[corner])
        if (face_normal[f].normalized().dot(own) >= crease_cos) n += face_normal[f];
      n = n.squaredNorm() > 0.0 ? n.normalized() : own;
      const Vec3& p = mesh.vertices[corner];
      for (double x : {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()}) v.push_back(float(x));
      if (material != nullptr) {
        const Vec3 base = material->use_body_color ? body_color_linear : material->base_color_linear;
        const Vec3 albedo = base.cwiseProduct(look->corner_color[t][k]);
        const Eigen::Vector2d& uv = look->corner_uv[t][k];
        for (double x : {albedo.x(), albedo.y(), albedo.z(), uv.x(), uv.y()})
          v.push_back(float(x));
      }
      idx.push_back(static_cast<unsigned>(idx.size()));
    }
  }
  if (look == nullptr) return upload(v, idx);
  Mesh m = upload_with_materials(v, idx);
  // Each part's texture index (stored + 1 above) becomes the GL texture.
  for (const TextureImage& image : look->textures) m.textures.push_back(upload_texture(image));
  m.parts = std::move(out_parts.parts);
  for (MeshPart& part : m.parts) part.texture = part.texture == 0 ? 0 : m.textures[part.texture - 1];
  if (glGetError() != GL_NO_ERROR) gl_fail("uploading a model's materials failed");
  return m;
}

Mesh make_floor_quad() {
  const std::vector<float> v = {-1, 0, -1, 0, 1, 0, 1,  0, -1, 0, 1, 0,
                                1,  0, 1,  0, 1, 0, -1, 0, 1,  0, 1, 0};
  return upload(v, {0, 2, 1, 0, 3, 2});
}

}  // namespace tumble
