// Mass properties of a closed polyhedron by the divergence theorem: each volume integral of
// 1, x, y, z, x², y², z², xy, yz, zx becomes a sum of surface integrals over the triangles
// (Mirtich 1996, "Fast and accurate computation of polyhedral mass properties", J. Graphics
// Tools 1(2); in the compact form of Eberly, "Polyhedral Mass Properties (Revisited)", 2002).
#include <array>

#include "tumble/mesh.hpp"

namespace tumble {
namespace {

// Eberly's subexpressions for one coordinate w of the three corners: f1 = Σw, f2 = Σw² + cross
// terms, f3 = the cubic terms, and g_i for the mixed products.
struct Subexpressions {
  double f1, f2, f3, g0, g1, g2;
};

Subexpressions subexpressions(double w0, double w1, double w2) {
  Subexpressions s;
  const double temp0 = w0 + w1;
  s.f1 = temp0 + w2;
  const double temp1 = w0 * w0;
  const double temp2 = temp1 + w1 * temp0;
  s.f2 = temp2 + w2 * s.f1;
  s.f3 = w0 * temp1 + w1 * temp2 + w2 * s.f2;
  s.g0 = s.f2 + w0 * (s.f1 + w0);
  s.g1 = s.f2 + w1 * (s.f1 + w1);
  s.g2 = s.f2 + w2 * (s.f1 + w2);
  return s;
}

}  // namespace

MassProperties mass_properties(const TriangleMesh& mesh) {
  MassProperties props;
  if (mesh.vertices.empty() || mesh.triangles.empty()) return props;

  // Integrate about the centre of the bounding box, not the file's origin: a model far from
  // its origin would otherwise lose digits to cancellation in the second moments.
  Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 origin = 0.5 * (lo + hi);

  // integral = {1, x, y, z, x², y², z², xy, yz, zx} over the solid, before Eberly's factors.
  std::array<double, 10> integral{};
  for (const auto& t : mesh.triangles) {
    const Vec3 p0 = mesh.vertices[t[0]] - origin;
    const Vec3 p1 = mesh.vertices[t[1]] - origin;
    const Vec3 p2 = mesh.vertices[t[2]] - origin;
    // d = (p1 - p0) x (p2 - p0): twice the area times the outward normal.
    const Vec3 d = (p1 - p0).cross(p2 - p0);
    const Subexpressions x = subexpressions(p0.x(), p1.x(), p2.x());
    const Subexpressions y = subexpressions(p0.y(), p1.y(), p2.y());
    const Subexpressions z = subexpressions(p0.z(), p1.z(), p2.z());
    integral[0] += d.x() * x.f1;
    integral[1] += d.x() * x.f2;
    integral[2] += d.y() * y.f2;
    integral[3] += d.z() * z.f2;
    integral[4] += d.x() * x.f3;
    integral[5] += d.y() * y.f3;
    integral[6] += d.z() * z.f3;
    integral[7] += d.x() * (p0.y() * x.g0 + p1.y() * x.g1 + p2.y() * x.g2);
    integral[8] += d.y() * (p0.z() * y.g0 + p1.z() * y.g1 + p2.z() * y.g2);
    integral[9] += d.z() * (p0.x() * z.g0 + p1.x() * z.g1 + p2.x() * z.g2);
  }
  integral[0] /= 6.0;
  for (int i = 1; i <= 3; ++i) integral[static_cast<std::size_t>(i)] /= 24.0;
  for (int i = 4; i <= 6; ++i) integral[static_cast<std::size_t>(i)] /= 60.0;
  for (int i = 7; i <= 9; ++i) integral[static_cast<std::size_t>(i)] /= 120.0;

  const double volume = integral[0];
  props.volume = volume;
  if (volume == 0.0) return props;
  const Vec3 c(integral[1] / volume, integral[2] / volume, integral[3] / volume);
  props.center_of_mass = origin + c;

  // Second moments about the centroid (parallel-axis theorem), then the inertia tensor
  // I = tr(S) 1 - S with S = ∫ r rᵀ dV about the centroid.
  const double sxx = integral[4] - volume * c.x() * c.x();
  const double syy = integral[5] - volume * c.y() * c.y();
  const double szz = integral[6] - volume * c.z() * c.z();
  const double sxy = integral[7] - volume * c.x() * c.y();
  const double syz = integral[8] - volume * c.y() * c.z();
  const double szx = integral[9] - volume * c.z() * c.x();
  Mat3& inertia = props.inertia_com;
  inertia << syy + szz, -sxy, -szx,  //
      -sxy, szz + sxx, -syz,         //
      -szx, -syz, sxx + syy;

  const PrincipalFrame frame = principal_frame(inertia);
  props.principal_moments = frame.moments;
  props.principal_axes = frame.axes;
  return props;
}

}  // namespace tumble
