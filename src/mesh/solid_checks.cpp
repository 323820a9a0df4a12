#include "solid_checks.hpp"

#include <algorithm>
#include <string>

#include "mesh_error.hpp"

namespace tumble::mesh_detail {

SurfaceMeasures measure_surface(const TriangleMesh& mesh) {
  SurfaceMeasures s;
  if (mesh.vertices.empty()) return s;
  Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  s.diagonal = (hi - lo).norm();
  const Vec3 centre = 0.5 * (lo + hi);
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - centre;
    const Vec3 d = (mesh.vertices[t[1]] - centre - a).cross(mesh.vertices[t[2]] - centre - a);
    s.area += 0.5 * d.norm();
    s.area_vector += 0.5 * d;
  }
  return s;
}

void check_solid(const std::filesystem::path& file, const SurfaceMeasures& surface,
                 const MassProperties& mass, double hull_volume, const char* what) {
  const std::string name = what;
  // Round-off in Σ area·normal grows like sqrt(n) ulps of the area; 1e-9 is far above it and
  // far below any real gap.
  if (surface.area_vector.norm() > 1e-9 * surface.area)
    throw_mesh_error(file, "not closed: " + name +
                               " does not enclose a volume (its area-weighted "
                               "normals sum to " +
                               format_point(surface.area_vector) + " m^2, not 0)");
  if (!(mass.volume > surface.zero_volume()) || !mass.inertia_com.allFinite())
    throw_mesh_error(file, "zero volume: " + name + " encloses " + format_number(mass.volume) +
                               " m^3 for " + format_number(surface.area) +
                               " m^2 of surface (it is flat or folded onto itself)");
  // The hull contains the solid; Qhull's facet merging may move its faces inward by round-off
  // only, so 1e-9 relative is ample.
  if (mass.volume > hull_volume * (1.0 + 1e-9))
    throw_mesh_error(file, "self-intersecting: " + name + " encloses " +
                               format_number(mass.volume) + " m^3, more than its convex hull's " +
                               format_number(hull_volume) +
                               " m^3 (overlapping parts are counted twice)");
  const Vec3& m = mass.principal_moments;
  const double trace = m.sum();
  const double slack = 1e-9 * std::abs(trace);
  const bool positive = m.minCoeff() > 1e-12 * std::abs(trace);
  const bool triangle =
      m[0] + m[1] >= m[2] - slack && m[1] + m[2] >= m[0] - slack && m[2] + m[0] >= m[1] - slack;
  if (!positive || !triangle)
    throw_mesh_error(file, "self-intersecting: the inertia of " + name +
                               " is not that of a solid (principal moments " + format_point(m) +
                               " per unit density: they must be positive and each at most the "
                               "sum of the other two)");
}

}  // namespace tumble::mesh_detail
