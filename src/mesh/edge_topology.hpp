#pragma once
// The edges of a welded triangle mesh: which are open (one triangle), non-manifold (more than
// two), or joined in the same direction by two triangles (inconsistent winding); and, over the
// manifold edges, making the winding consistent.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tumble::mesh_detail {

using Triangle = std::array<std::uint32_t, 3>;
using Edge = std::array<std::uint32_t, 2>;  ///< vertex indices, smaller first

struct EdgeCensus {
  std::size_t edges = 0;         ///< distinct undirected edges
  std::size_t open = 0;          ///< used by one triangle
  std::size_t non_manifold = 0;  ///< used by three or more
  std::size_t misoriented = 0;   ///< used by two triangles in the same direction
  static constexpr std::size_t kExamples = 3;
  std::vector<Edge> open_examples, non_manifold_examples, misoriented_examples;  ///< the first few
  bool closed_manifold() const { return open == 0 && non_manifold == 0; }
};

/// Counts every kind of edge; examples are the first in vertex order (earliest in the file).
EdgeCensus census_edges(const std::vector<Triangle>& triangles);

/// For a closed manifold mesh (every edge in exactly two triangles): which triangles to flip so
/// that every edge is used once in each direction, keeping the lowest-numbered triangle of each
/// connected part as it is and flipping the fewest otherwise. Empty when that is impossible
/// (a non-orientable surface such as a Klein bottle).
std::vector<bool> consistent_flips(const std::vector<Triangle>& triangles);

/// Connected parts (shells) through shared edges: component[t] in 0..count-1, numbered in the
/// order of their lowest triangle.
struct Components {
  std::vector<std::uint32_t> component;
  std::size_t count = 0;
};
Components edge_connected_components(const std::vector<Triangle>& triangles);

}  // namespace tumble::mesh_detail
