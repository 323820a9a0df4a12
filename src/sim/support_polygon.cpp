#include "support_polygon.hpp"

#include <algorithm>
#include <cmath>

namespace tumble {
namespace {

// 2-D cross product of (a − o) and (b − o): > 0 when o, a, b turn counter-clockwise.
double cross(const PlanePoint& o, const PlanePoint& a, const PlanePoint& b) {
  return (a.x - o.x) * (b.z - o.z) - (a.z - o.z) * (b.x - o.x);
}

}  // namespace

int support_polygon(PlanePoint* p, int n, PlanePoint* hull) {
  std::sort(p, p + n, [](const PlanePoint& l, const PlanePoint& r) {
    return l.x < r.x || (l.x == r.x && (l.z < r.z || (l.z == r.z && l.index < r.index)));
  });
  if (n < 3) {
    std::copy(p, p + n, hull);
    return n;
  }
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (int i = n - 2, t = k + 1; i >= 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  return k - 1;  // the last corner repeats the first
}

bool strictly_inside(const PlanePoint* polygon, int n, double x, double z, double margin) {
  if (n < 3) return false;
  const PlanePoint q{x, z, -1};
  for (int i = 0; i < n; ++i) {
    const PlanePoint &a = polygon[i], &b = polygon[(i + 1) % n];
    // sqrt of the squares, not hypot: metres never overflow a double, and this runs in every
    // derivative evaluation of a resting face.
    const double dx = b.x - a.x, dz = b.z - a.z;
    if (cross(a, b, q) <= margin * std::sqrt(dx * dx + dz * dz)) return false;
  }
  return true;
}

}  // namespace tumble
