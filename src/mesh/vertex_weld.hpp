#pragma once
// Welding a triangle soup by position: vertices closer than a tolerance relative to the model's
// size become one, whatever their normals, UVs or mesh of origin.

#include <cstdint>
#include <vector>

#include "tumble/math.hpp"

namespace tumble::mesh_detail {

struct Weld {
  std::vector<Vec3> vertices;           ///< distinct positions, in order of first use
  std::vector<std::uint32_t> index_of;  ///< soup vertex -> welded vertex
  double tolerance = 0;                 ///< the distance used, m
};

/// The weld tolerance for points spanning `diagonal` (bounding-box diagonal) whose largest
/// coordinate magnitude is `max_abs`: the larger of 1e-7 of the diagonal and four float32 ulps
/// of the largest coordinate (files store float32, so closer points are the same point).
double weld_tolerance(double diagonal, double max_abs);

/// Welds deterministically: each point joins the earliest earlier point within the tolerance
/// that is itself kept, else it is kept; the result depends only on the input order.
Weld weld_vertices(const std::vector<Vec3>& positions);

}  // namespace tumble::mesh_detail
