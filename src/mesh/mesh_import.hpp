#pragma once
// Reading a model file through assimp into one triangle soup: every aiMesh under every node,
// node transforms baked in (in double precision), winding kept outward under mirroring
// transforms, `scale` applied. No welding and no checks of the geometry yet.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tumble/mesh.hpp"

namespace tumble::mesh_detail {

struct TriangleSoup {
  std::vector<Vec3> positions;  ///< metres, file frame
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Per triangle of `triangles` (its corners in the same order), or empty when the file has
  /// no material of its own and no vertex colours.
  MeshAppearance appearance;
};

/// Checks the file (exists, allow-listed extension, size) and reads it, with its materials,
/// textures (decoded) and vertex colours. Throws tumble::Error naming the file for every
/// failure, with assimp's own text when assimp cannot parse it, and naming the texture file
/// when a texture cannot be read.
TriangleSoup import_triangle_soup(const std::filesystem::path& file,
                                  const MeshLoadOptions& options);

}  // namespace tumble::mesh_detail
