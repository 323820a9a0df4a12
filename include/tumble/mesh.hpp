#pragma once
/// Closed triangle meshes as rigid bodies: loading through assimp, welding, topology checks and
/// repairs, exact mass properties (divergence theorem) and the convex hull (Qhull); reducing a
/// hull face on the floor to its support polygon is the physics' (src/sim/floor_contact.cpp).
/// Plain data in, plain data out: this layer knows nothing of scenes, worlds or GL.
/// Everything is in the model file's own frame (after `scale`, in metres); nothing is moved to the
/// centre of mass or rotated to principal axes, so "identity" always means "as the file has it".
/// Reference for users: docs/meshes.md.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tumble/math.hpp"

namespace tumble {

/// What `load_mesh_body` may change in a model that is not a clean closed solid.
enum class MeshRepair {
  None,    ///< nothing: every defect is an error
  Orient,  ///< make the winding consistent and every shell face outward (flip inside-out parts)
  Hull,    ///< replace the model by its convex hull (simulated and rendered); any input with volume
};

struct MeshLoadOptions {
  Vec3 scale = Vec3::Ones();  ///< file units -> metres, per axis; each finite and > 0
  MeshRepair repair = MeshRepair::None;
  std::uintmax_t max_file_bytes = 256u << 20;  ///< the model file and each file it references
  std::size_t max_triangles = 2'000'000;       ///< after triangulation, over all meshes and nodes
  /// Decoded pixels of each texture (width × height): a small PNG or JPEG may unpack into
  /// gigabytes. 64 Mpx: an 8192 × 8192 texture.
  std::uint64_t max_texture_pixels = 8192ull * 8192ull;
};

/// Welded, consistently wound triangles: counter-clockwise seen from outside (the right-hand
/// normal points out of the solid). File frame, metres. No triangle has zero area.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Mass properties of the solid at unit density (1 kg/m^3): multiply the volume and the inertia
/// by the density to get the mass and the inertia in kg, kg·m².
struct MassProperties {
  double volume = 0;                   ///< m^3, > 0 for a valid solid
  Vec3 center_of_mass = Vec3::Zero();  ///< file frame, m
  Mat3 inertia_com = Mat3::Zero();     ///< about the centre of mass, file axes, unit density
  /// Principal moments, unit density: principal_moments[i] is the moment about column i of
  /// `principal_axes` (not sorted; see below).
  Vec3 principal_moments = Vec3::Zero();
  /// Rotation (det +1) whose columns are principal axes in the file frame, chosen as the one
  /// closest to the identity: a box-shaped model keeps the file's axes (identity, its moments
  /// in x, y, z order), and where moments are equal (within 1e-6 relative: a cube, a sphere, a
  /// regular tetrahedron) the file's own axes are kept in the equal-moment subspace.
  Mat3 principal_axes = Mat3::Identity();
};

/// Principal moments and axes of a symmetric inertia tensor, by the rule of
/// MassProperties::principal_axes (closest rotation to the identity; equal moments keep the
/// given axes). inertia == axes * diag(moments) * axes^T to 1e-6 of the largest moment.
struct PrincipalFrame {
  Vec3 moments = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
};
PrincipalFrame principal_frame(const Mat3& inertia);

/// A texture as decoded from its PNG or JPEG: RGBA8, rows top-down as in the file (the top row
/// is v = 1 in assimp's texture coordinates, whose origin is the bottom left).
struct TextureImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  ///< 4 bytes per pixel, sRGB-encoded colour, straight alpha
  std::string source;              ///< the file (or "FILE, embedded texture N") it came from
};

/// One material of a model: its base colour and, optionally, a texture multiplied into it.
struct MeshMaterial {
  std::string name;                      ///< the file's name for it ("" when unnamed)
  Vec3 base_color_linear = Vec3::Ones();  ///< linear RGB (glTF baseColorFactor, MTL Kd)
  int texture = -1;                      ///< index into MeshAppearance::textures, -1: none
  /// Not the file's: the parts of a model that name no material of their own are drawn in the
  /// body's colour (times their vertex colours).
  bool use_body_color = false;
};

/// How a model's file says it looks, per drawn triangle (aligned with MeshBody::mesh.triangles).
/// Empty (`has_materials()` false) for a model whose file carries no material of its own and no
/// vertex colours: it is drawn in the body's colour. docs/meshes.md says which file fields count.
struct MeshAppearance {
  std::vector<MeshMaterial> materials;
  std::vector<TextureImage> textures;
  /// Per triangle: index into `materials`.
  std::vector<std::uint32_t> triangle_material;
  /// Per triangle corner: linear RGB multiplied into the material's colour (per-vertex colours;
  /// ones where the file has none).
  std::vector<std::array<Vec3, 3>> corner_color;
  /// Per triangle corner: texture coordinates (u, v), origin bottom left; zeros without UVs.
  std::vector<std::array<Eigen::Vector2d, 3>> corner_uv;
  bool has_materials() const { return !triangle_material.empty(); }
};

/// A loaded model, checked and ready to become a body.
struct MeshBody {
  TriangleMesh mesh;    ///< what is rendered (after any repair)
  MassProperties mass;  ///< of the solid that is simulated (the hull when repair = hull)
  std::vector<Vec3> hull_vertices;       ///< convex hull vertices, file frame, sorted by (x, y, z)
  std::size_t hull_faces = 0;            ///< faces of the hull, coplanar triangles merged into one
  std::string repair_note;               ///< what a repair changed; "" when nothing was changed
  std::size_t source_triangles = 0;      ///< triangles in the file, after triangulation
  std::size_t welded_vertices = 0;       ///< distinct vertices after welding
  std::size_t degenerate_triangles = 0;  ///< zero-area triangles dropped (see docs/meshes.md)
  /// Its materials, textures and vertex colours, per triangle of `mesh` (none after
  /// repair = "hull", whose triangles are not the file's).
  MeshAppearance appearance;
};

/// Loads and checks a closed model; throws tumble::Error (BadInput, the file as its location,
/// so `describe()` reads "FILE: problem") for a missing, unreadable, unparseable or too large
/// file, a format outside the allow-list, and a model that is not a valid solid (not closed,
/// non-manifold, inconsistently wound, inside-out, without volume, self-intersecting), each
/// with counts and an example location in file units. A texture that a material names and that
/// is missing, unreadable, outside the model's folder, too large or not a PNG or JPEG is an
/// error too, naming the texture file.
MeshBody load_mesh_body(const std::filesystem::path& file, const MeshLoadOptions& options);

/// The file extensions `load_mesh_body` accepts, lower case, without the dot.
const std::vector<std::string>& mesh_file_extensions();

/// Volume, centre of mass and inertia of the solid bounded by a closed, outward-wound mesh, by
/// the divergence theorem (Mirtich 1996, "Fast and accurate computation of polyhedral mass
/// properties"; Eberly, "Polyhedral Mass Properties (Revisited)"). An inside-out mesh gives a
/// negative volume; an open one, a meaningless result: check the topology first.
MassProperties mass_properties(const TriangleMesh& mesh);

/// The convex hull as a closed, outward-wound triangle mesh.
struct ConvexHull {
  TriangleMesh mesh;      ///< vertices sorted by (x, y, z); faces fan-triangulated
  std::size_t faces = 0;  ///< hull faces before triangulation (a cube: 6)
};

/// Convex hull of a point set (Qhull, libqhull_r, with its default facet merging). Throws
/// tumble::Error (BadInput, no location) when the points span no volume (fewer than 4, all on
/// a line or in a plane, to Qhull's precision), saying so.
ConvexHull convex_hull(const std::vector<Vec3>& points);
/// The vertices of convex_hull(points), sorted by (x, y, z).
std::vector<Vec3> convex_hull_vertices(const std::vector<Vec3>& points);

}  // namespace tumble
