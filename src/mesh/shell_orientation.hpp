#pragma once
// Which way each closed shell of a consistently wound mesh faces. A solid's outer shells must
// face outward (positive signed volume) and the shells of its cavities inward: a shell nested
// inside an odd number of others bounds a cavity. A shell facing the wrong way is inside-out.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "edge_topology.hpp"
#include "tumble/math.hpp"

namespace tumble::mesh_detail {

struct Shell {
  std::vector<std::uint32_t> triangles;  ///< indices into the mesh's triangles
  double signed_volume = 0;              ///< m^3; > 0 when it faces outward
  std::size_t depth = 0;                 ///< how many other shells enclose it
  bool inside_out = false;      ///< faces the wrong way for its depth (outward at odd depth, ...)
  bool crosses = false;         ///< partly inside, partly outside another shell: they intersect
  Vec3 example = Vec3::Zero();  ///< a vertex of it, for messages
};

/// The shells of a closed, manifold, consistently wound mesh, in order of their lowest triangle.
std::vector<Shell> orient_shells(const std::vector<Vec3>& vertices,
                                 const std::vector<Triangle>& triangles);

/// Generalised winding number of a closed triangle surface at `p`: the solid angle it subtends
/// over 4 pi (Van Oosterom & Strackee 1983). +1 inside an outward shell, 0 outside, -1 inside an
/// inward one.
double winding_number(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles,
                      const std::vector<std::uint32_t>& subset, const Vec3& p);

}  // namespace tumble::mesh_detail
