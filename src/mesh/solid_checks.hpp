#pragma once
// Last checks that a mesh bounds a physical solid, each with a tolerance relative to the
// model's own size (never an absolute number): the surface encloses (Σ area·normal ≈ 0), the
// volume is positive and not above the convex hull's, the principal moments are positive and
// obey the triangle inequality. A closed, consistently wound mesh that fails one of these
// intersects itself.

#include <filesystem>

#include "tumble/mesh.hpp"

namespace tumble::mesh_detail {

struct SurfaceMeasures {
  double area = 0;                  ///< m^2
  Vec3 area_vector = Vec3::Zero();  ///< Σ area · outward normal, m^2 (0 for a closed surface)
  double diagonal = 0;              ///< of the bounding box, m
  /// Volumes at or below this are zero to round-off: 1e-9 · area · diagonal.
  double zero_volume() const { return 1e-9 * area * diagonal; }
};
SurfaceMeasures measure_surface(const TriangleMesh& mesh);

/// Throws tumble::Error naming `file` when a check fails; `what` names the solid in messages
/// ("the mesh", "its convex hull").
void check_solid(const std::filesystem::path& file, const SurfaceMeasures& surface,
                 const MassProperties& mass, double hull_volume, const char* what);

}  // namespace tumble::mesh_detail
