#include "edge_topology.hpp"

#include <algorithm>
#include <tuple>

namespace tumble::mesh_detail {
namespace {

struct HalfEdge {
  Edge edge;           // undirected, smaller vertex first
  std::uint32_t face;  // triangle using it
  bool forward;        // the triangle runs edge[0] -> edge[1]

  bool operator<(const HalfEdge& o) const {
    return std::tie(edge, face, forward) < std::tie(o.edge, o.face, o.forward);
  }
};

// Every triangle's three half-edges, sorted so that the uses of one edge are adjacent.
std::vector<HalfEdge> sorted_half_edges(const std::vector<Triangle>& triangles) {
  std::vector<HalfEdge> half;
  half.reserve(3 * triangles.size());
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[static_cast<std::size_t>(k)];
      const std::uint32_t b = t[static_cast<std::size_t>((k + 1) % 3)];
      half.push_back({{std::min(a, b), std::max(a, b)}, f, a < b});
    }
  }
  std::sort(half.begin(), half.end());
  return half;
}

// Calls visit(first, last) for each run of half-edges on one undirected edge.
template <typename Visit>
void for_each_edge(const std::vector<HalfEdge>& half, Visit visit) {
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].edge == half[i].edge) ++j;
    visit(i, j);
    i = j;
  }
}

struct Neighbour {
  std::uint32_t face;
  bool same_direction;  // both triangles run the shared edge the same way
};

// Triangle adjacency over the edges used by exactly two triangles.
std::vector<std::vector<Neighbour>> manifold_neighbours(const std::vector<Triangle>& triangles) {
  const std::vector<HalfEdge> half = sorted_half_edges(triangles);
  std::vector<std::vector<Neighbour>> neighbours(triangles.size());
  for_each_edge(half, [&](std::size_t i, std::size_t j) {
    if (j - i != 2) return;
    const HalfEdge& a = half[i];
    const HalfEdge& b = half[i + 1];
    if (a.face == b.face) return;  // a triangle using one edge twice is degenerate
    const bool same = a.forward == b.forward;
    neighbours[a.face].push_back({b.face, same});
    neighbours[b.face].push_back({a.face, same});
  });
  return neighbours;
}

}  // namespace

EdgeCensus census_edges(const std::vector<Triangle>& triangles) {
  const std::vector<HalfEdge> half = sorted_half_edges(triangles);
  EdgeCensus census;
  auto note = [](std::vector<Edge>& examples, const Edge& e) {
    if (examples.size() < EdgeCensus::kExamples) examples.push_back(e);
  };
  for_each_edge(half, [&](std::size_t i, std::size_t j) {
    ++census.edges;
    const std::size_t uses = j - i;
    if (uses == 1) {
      ++census.open;
      note(census.open_examples, half[i].edge);
    } else if (uses > 2) {
      ++census.non_manifold;
      note(census.non_manifold_examples, half[i].edge);
    } else if (half[i].forward == half[i + 1].forward) {
      ++census.misoriented;
      note(census.misoriented_examples, half[i].edge);
    }
  });
  return census;
}

std::vector<bool> consistent_flips(const std::vector<Triangle>& triangles) {
  const auto neighbours = manifold_neighbours(triangles);
  const std::size_t n = triangles.size();
  std::vector<bool> flip(n, false);
  std::vector<bool> seen(n, false);
  std::vector<std::uint32_t> part, stack;
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (seen[seed]) continue;
    // Walk one connected part: a neighbour joined in the same direction must be
    // flipped relative to its neighbour; a contradiction means no orientation exists.
    part.clear();
    stack.assign(1, seed);
    seen[seed] = true;
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      part.push_back(f);
      for (const Neighbour& nb : neighbours[f]) {
        const bool wanted = flip[f] != nb.same_direction;
        if (!seen[nb.face]) {
          seen[nb.face] = true;
          flip[nb.face] = wanted;
          stack.push_back(nb.face);
        } else if (flip[nb.face] != wanted) {
          return {};
        }
      }
    }
    // Flip the minority, so a mesh with a few stray triangles keeps the orientation most of
    // its triangles have (whether that is outward is decided later, by volume).
    const auto flipped = static_cast<std::size_t>(
        std::count_if(part.begin(), part.end(), [&](std::uint32_t f) { return flip[f]; }));
    if (2 * flipped > part.size())
      for (std::uint32_t f : part) flip[f] = !flip[f];
  }
  return flip;
}

Components edge_connected_components(const std::vector<Triangle>& triangles) {
  // Union-find over triangles sharing an edge (any number of uses).
  const std::size_t n = triangles.size();
  std::vector<std::uint32_t> parent(n);
  for (std::uint32_t f = 0; f < n; ++f) parent[f] = f;
  auto find = [&](std::uint32_t f) {
    while (parent[f] != f) {
      parent[f] = parent[parent[f]];
      f = parent[f];
    }
    return f;
  };
  const std::vector<HalfEdge> half = sorted_half_edges(triangles);
  for_each_edge(half, [&](std::size_t i, std::size_t j) {
    for (std::size_t k = i + 1; k < j; ++k) {
      const std::uint32_t a = find(half[i].face), b = find(half[k].face);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is the lowest triangle
    }
  });
  Components c;
  c.component.assign(n, 0);
  std::vector<std::uint32_t> number(n, 0);
  for (std::uint32_t f = 0; f < n; ++f) {
    const std::uint32_t root = find(f);
    if (root == f) number[f] = static_cast<std::uint32_t>(c.count++);
    c.component[f] = number[root];
  }
  return c;
}

}  // namespace tumble::mesh_detail
