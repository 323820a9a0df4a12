#pragma once
// The renderer's GL building blocks: shader programs from the embedded GLSL, and the meshes it
// draws (unit cube, unit-diameter sphere, floor square), uploaded once. Needs a current context.

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <string>
#include <vector>

#include "tumble/mesh.hpp"

namespace tumble {

/// Throws tumble::Error (Environment) "OpenGL: what".
[[noreturn]] void gl_fail(const std::string& what);

/// Compiles and links shaders/<vert_name> with shaders/<frag_name>; fragment shaders get the
/// version line and shaders/common.glsl (shared lighting) in front.
GLuint link_program(const char* vert_name, const char* frag_name);

/// A run of a model's indices drawn with one texture (or none).
struct MeshPart {
  GLsizei first = 0, count = 0;
  GLuint texture = 0;  ///< 0: untextured
};

/// An indexed triangle mesh of interleaved position + normal (attributes 0 and 1); a model with
/// materials also has a linear albedo (2) and texture coordinates (3) per corner.
struct Mesh {
  GLuint vao = 0, vbo = 0, ebo = 0;
  GLsizei count = 0;
  /// A marked sphere: its first `marked` indices are the marking (drawn in a second colour).
  GLsizei marked = 0;
  /// A model drawn in its own materials: its runs of indices, one per material (in order); empty
  /// for a mesh drawn in one uniform colour.
  std::vector<MeshPart> parts;
  std::vector<GLuint> textures;  ///< owned: the model's textures
  void release();  ///< deletes the GL objects (an explicit call: the context must be current)
};

Mesh make_cube();                                     ///< [-0.5, 0.5]³, flat face normals
Mesh make_sphere(int rings = 16, int segments = 32);  ///< diameter 1, smooth normals
/// The same sphere, its triangles ordered so that the first `marked` indices are every other
/// octant (x·y·z > 0): drawn in a second colour, the marking shows the ball's spin.
Mesh make_marked_sphere(int rings = 16, int segments = 32);
Mesh make_floor_quad();                               ///< [-1, 1]² at y = 0, normal +y
/// A model's triangles (model frame), with normals computed per corner: the area-weighted
/// average of the normals of the faces around the vertex that lie within 40° of the corner's
/// own face, so curved surfaces shade smoothly and edges stay sharp.
/// With `look` (its materials, textures and vertex colours, per triangle), each corner also
/// carries its linear albedo (material colour × vertex colour; `body_color_linear` for the parts
/// whose material is not the file's) and texture coordinates, the triangles are grouped by
/// material, and each texture is uploaded (sRGB, mipmapped, repeating).
Mesh make_model(const TriangleMesh& mesh, const MeshAppearance* look = nullptr,
                const Vec3& body_color_linear = Vec3::Ones());

}  // namespace tumble
