#include "shell_orientation.hpp"

#include <cmath>

namespace tumble::mesh_detail {

double winding_number(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles,
                      const std::vector<std::uint32_t>& subset, const Vec3& p) {
  // Van Oosterom & Strackee: tan(Omega/2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| +
  // (c.a)|b|) for a, b, c the corners relative to p.
  double omega = 0.0;
  for (std::uint32_t f : subset) {
    const Triangle& t = triangles[f];
    const Vec3 a = vertices[t[0]] - p, b = vertices[t[1]] - p, c = vertices[t[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    omega += 2.0 * std::atan2(numerator, denominator);
  }
  return omega / (4.0 * kPi);
}

std::vector<Shell> orient_shells(const std::vector<Vec3>& vertices,
                                 const std::vector<Triangle>& triangles) {
  const Components parts = edge_connected_components(triangles);
  std::vector<Shell> shells(parts.count);
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    shells[parts.component[f]].triangles.push_back(f);

  // Signed volumes about the centre of the bounding box: the divergence theorem's
  // sum of det(a, b, c) / 6 loses least to cancellation near the model.
  Vec3 lo = vertices.empty() ? Vec3::Zero() : vertices[0];
  Vec3 hi = lo;
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  std::vector<Vec3> shell_lo(shells.size()), shell_hi(shells.size());
  for (std::size_t s = 0; s < shells.size(); ++s) {
    Shell& shell = shells[s];
    double six_volume = 0.0;
    shell_lo[s] = shell_hi[s] = vertices[triangles[shell.triangles[0]][0]];
    for (std::uint32_t f : shell.triangles) {
      const Triangle& t = triangles[f];
      const Vec3 a = vertices[t[0]] - centre, b = vertices[t[1]] - centre,
                 c = vertices[t[2]] - centre;
      six_volume += a.dot(b.cross(c));
      for (std::uint32_t v : t) {
        shell_lo[s] = shell_lo[s].cwiseMin(vertices[v]);
        shell_hi[s] = shell_hi[s].cwiseMax(vertices[v]);
      }
    }
    shell.signed_volume = six_volume / 6.0;
    shell.example = vertices[triangles[shell.triangles[0]][0]];
  }

  if (shells.size() > 1) {
    // Nesting: is shell s inside shell o? Valid shells do not cross, so any point of s
    // decides; a few (the centroid of its first triangle and its six extreme vertices) also
    // reveal shells that do cross. A bounding-box test first keeps the cost at a few winding
    // numbers per pair of overlapping boxes.
    for (std::size_t s = 0; s < shells.size(); ++s) {
      const Triangle& t = triangles[shells[s].triangles[0]];
      std::vector<Vec3> probes{(vertices[t[0]] + vertices[t[1]] + vertices[t[2]]) / 3.0};
      for (int axis = 0; axis < 3; ++axis) {
        std::uint32_t low = t[0], high = t[0];
        for (std::uint32_t f : shells[s].triangles)
          for (std::uint32_t v : triangles[f]) {
            if (vertices[v][axis] < vertices[low][axis]) low = v;
            if (vertices[v][axis] > vertices[high][axis]) high = v;
          }
        probes.push_back(vertices[low]);
        probes.push_back(vertices[high]);
      }
      for (std::size_t o = 0; o < shells.size(); ++o) {
        if (o == s) continue;
        int inside = 0, outside = 0;
        for (const Vec3& probe : probes) {
          if ((probe.array() < shell_lo[o].array()).any() ||
              (probe.array() > shell_hi[o].array()).any()) {
            ++outside;
            continue;
          }
          const double w =
              std::abs(winding_number(vertices, triangles, shells[o].triangles, probe));
          if (w > 0.75)
            ++inside;
          else if (w < 0.25)
            ++outside;  // in between: on o's surface, which decides nothing
        }
        if (inside > 0 && outside > 0) shells[s].crosses = true;
        if (inside > 0 && outside == 0) ++shells[s].depth;
      }
    }
  }
  for (Shell& shell : shells) {
    const bool should_face_outward = shell.depth % 2 == 0;
    shell.inside_out = (shell.signed_volume > 0.0) != should_face_outward;
  }
  return shells;
}

}  // namespace tumble::mesh_detail
