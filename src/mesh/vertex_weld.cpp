#include "vertex_weld.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <tuple>

namespace tumble::mesh_detail {

double weld_tolerance(double diagonal, double max_abs) {
  // 2^-21 = four ulps of a float32 at the top of its binade.
  return std::max(1e-7 * diagonal, std::ldexp(max_abs, -21));
}

namespace {

bool lexicographic_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

using Cell = std::array<std::int64_t, 3>;

}  // namespace

Weld weld_vertices(const std::vector<Vec3>& positions) {
  Weld weld;
  const std::size_t n = positions.size();
  weld.index_of.assign(n, 0);
  if (n == 0) return weld;

  Vec3 lo = positions[0], hi = positions[0];
  for (const Vec3& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double max_abs = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  weld.tolerance = weld_tolerance((hi - lo).norm(), max_abs);

  // 1. Exact duplicates (the common case: one vertex per face corner in OBJ, STL, glTF with
  //    flat normals) by sorting; each group is represented by its earliest member.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (lexicographic_less(positions[a], positions[b])) return true;
    if (lexicographic_less(positions[b], positions[a])) return false;
    return a < b;
  });
  std::vector<std::uint32_t> exact(n);  // soup vertex -> earliest vertex at the same position
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = order[i];
    exact[v] = (i > 0 && positions[order[i - 1]] == positions[v]) ? exact[order[i - 1]] : v;
  }
  std::vector<std::uint32_t> distinct;  // earliest members, in input order
  for (std::uint32_t v = 0; v < n; ++v)
    if (exact[v] == v) distinct.push_back(v);

  // 2. Points within the tolerance, through a grid of cells twice the tolerance wide: a point's
  //    neighbours lie in at most 2 cells per axis. The cells are a sorted vector searched by
  //    binary search, so no hash order can leak into the result.
  const double cell_size = 2.0 * weld.tolerance;
  const bool by_grid = cell_size > 0.0 && std::isfinite(cell_size);
  auto cell_coordinate = [&](double x, int axis) {
    return static_cast<std::int64_t>(std::floor((x - lo[axis]) / cell_size));
  };
  std::vector<std::pair<Cell, std::uint32_t>> cells;  // (cell, distinct vertex)
  if (by_grid) {
    cells.reserve(distinct.size());
    for (std::uint32_t v : distinct) {
      const Vec3& p = positions[v];
      cells.push_back(
          {{cell_coordinate(p.x(), 0), cell_coordinate(p.y(), 1), cell_coordinate(p.z(), 2)}, v});
    }
    std::sort(cells.begin(), cells.end());
  }

  std::vector<std::uint32_t> kept(n, 0);  // distinct vertex -> the distinct vertex it joined
  std::vector<std::uint32_t> welded_index(n, 0);
  const double tolerance_squared = weld.tolerance * weld.tolerance;
  for (std::uint32_t v : distinct) {
    std::uint32_t joined = v;
    if (by_grid) {
      const Vec3& p = positions[v];
      std::array<std::int64_t, 3> first{}, last{};
      for (int axis = 0; axis < 3; ++axis) {
        first[static_cast<std::size_t>(axis)] = cell_coordinate(p[axis] - weld.tolerance, axis);
        last[static_cast<std::size_t>(axis)] = cell_coordinate(p[axis] + weld.tolerance, axis);
      }
      for (std::int64_t x = first[0]; x <= last[0]; ++x)
        for (std::int64_t y = first[1]; y <= last[1]; ++y)
          for (std::int64_t z = first[2]; z <= last[2]; ++z) {
            const Cell cell{x, y, z};
            auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(cell, 0u));
            for (; it != cells.end() && it->first == cell; ++it) {
              const std::uint32_t u = it->second;
              // Only earlier points that were kept themselves: no chains, order-determined.
              if (u < joined && kept[u] == u &&
                  (positions[u] - p).squaredNorm() <= tolerance_squared)
                joined = u;
            }
          }
    }
    kept[v] = joined;
    if (joined == v) {
      welded_index[v] = static_cast<std::uint32_t>(weld.vertices.size());
      weld.vertices.push_back(positions[v]);
    } else {
      welded_index[v] = welded_index[joined];
    }
  }
  for (std::uint32_t v = 0; v < n; ++v) weld.index_of[v] = welded_index[kept[exact[v]]];
  return weld;
}

}  // namespace tumble::mesh_detail
