// Contact-point reduction for a flat face resting on the floor: a hull face can put dozens of
// vertices on the floor at once, but the resting-contact problem only needs the corners of
// their support polygon (any force distribution over the face can be carried by its corners),
// and an LCP over few points is cheap and well-conditioned. When even the corners are too
// many, the most extreme ones (greedy farthest-point order) keep the polygon's extent.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "tumble/mesh.hpp"

namespace tumble {
namespace {

struct Point2 {
  double x, y;
};

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double distance_squared(const Point2& a, const Point2& b) {
  return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
}

}  // namespace

std::vector<int> reduce_support_points(const std::vector<Vec3>& points, const Vec3& normal,
                                       int max_points) {
  std::vector<int> chosen;
  if (max_points <= 0 || points.empty()) return chosen;
  const double normal_length = normal.norm();
  if (!(normal_length > 0.0) || !std::isfinite(normal_length)) return chosen;
  const Vec3 n = normal / normal_length;

  // A basis (u, v) of the plane: u from the file axis least aligned with the normal, so the
  // result does not depend on anything but the inputs.
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[least])) least = k;
  const Vec3 u = (Vec3::Unit(least) - n[least] * n).normalized();
  const Vec3 v = n.cross(u);
  std::vector<Point2> q(points.size());
  double extent = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    q[i] = {points[i].dot(u), points[i].dot(v)};
    extent = std::max(extent, distance_squared(q[i], q[0]));
  }
  extent = std::sqrt(extent);
  // Corners closer than this to the line through their neighbours are not corners: points on
  // an edge of the face, within round-off of the face's size.
  const double collinear = 1e-9 * extent * extent;

  // Andrew's monotone chain over indices sorted by (x, y, index): deterministic, and exact
  // duplicates keep the lower index (the later copy is skipped).
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Point2 &pa = q[static_cast<std::size_t>(a)], &pb = q[static_cast<std::size_t>(b)];
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    return a < b;
  });
  std::vector<int> unique;
  for (int i : order)
    if (unique.empty() || q[static_cast<std::size_t>(unique.back())].x != q[static_cast<std::size_t>(i)].x ||
        q[static_cast<std::size_t>(unique.back())].y != q[static_cast<std::size_t>(i)].y)
      unique.push_back(i);
  auto at = [&](int i) -> const Point2& { return q[static_cast<std::size_t>(i)]; };

  std::vector<int> corners;
  if (unique.size() <= 2) {
    corners = unique;
  } else {
    std::vector<int> hull(2 * unique.size());
    std::size_t k = 0;
    for (int i : unique) {  // lower chain
      while (k >= 2 && cross(at(hull[k - 2]), at(hull[k - 1]), at(i)) <= collinear) --k;
      hull[k++] = i;
    }
    const std::size_t lower = k + 1;
    for (std::size_t j = unique.size() - 1; j-- > 0;) {  // upper chain
      const int i = unique[j];
      while (k >= lower && cross(at(hull[k - 2]), at(hull[k - 1]), at(i)) <= collinear) --k;
      hull[k++] = i;
    }
    hull.resize(k - 1);  // the last point repeats the first
    corners = hull;      // counter-clockwise about `normal`
    if (corners.size() < 3) {
      // All on one line: its two ends.
      corners = {unique.front(), unique.back()};
    }
  }

  // Greedy most-extreme-first order over the corners.
  const std::size_t m = corners.size();
  Point2 centroid{0.0, 0.0};
  for (int c : corners) {
    centroid.x += at(c).x / static_cast<double>(m);
    centroid.y += at(c).y / static_cast<double>(m);
  }
  auto better = [](double score, int index, double best_score, int best_index) {
    return score > best_score || (score == best_score && index < best_index);
  };
  std::vector<bool> taken(m, false);
  std::vector<std::size_t> picked;  // positions in `corners`
  auto pick_farthest_from = [&](const Point2& from) {
    std::size_t best = m;
    double best_score = -1.0;
    for (std::size_t i = 0; i < m; ++i) {
      if (taken[i]) continue;
      const double score = distance_squared(at(corners[i]), from);
      if (best == m || better(score, corners[i], best_score, corners[best])) {
        best = i;
        best_score = score;
      }
    }
    return best;
  };
  const auto limit = static_cast<std::size_t>(max_points);
  if (m > 0 && limit >= 1) {
    std::size_t first = pick_farthest_from(centroid);
    taken[first] = true;
    picked.push_back(first);
  }
  if (m > 1 && limit >= 2) {
    std::size_t second = pick_farthest_from(at(corners[picked[0]]));
    taken[second] = true;
    picked.push_back(second);
  }
  while (picked.size() < std::min(m, limit)) {
    // Corners of a convex polygon: an unpicked corner lies outside the polygon of the picked
    // ones, beyond the chord between the picked corners before and after it (in polygon
    // order); its distance from that chord is how much support it adds.
    std::vector<std::size_t> sorted = picked;
    std::sort(sorted.begin(), sorted.end());
    std::size_t best = m;
    double best_score = -1.0;
    for (std::size_t i = 0; i < m; ++i) {
      if (taken[i]) continue;
      const auto after = std::upper_bound(sorted.begin(), sorted.end(), i);
      const std::size_t next = after == sorted.end() ? sorted.front() : *after;
      const std::size_t prev = after == sorted.begin() ? sorted.back() : *(after - 1);
      const Point2 &a = at(corners[prev]), &b = at(corners[next]), &c = at(corners[i]);
      const double chord = std::sqrt(distance_squared(a, b));
      const double score = chord > 0.0 ? std::abs(cross(a, b, c)) / chord
                                       : std::sqrt(distance_squared(a, c));
      if (best == m || better(score, corners[i], best_score, corners[best])) {
        best = i;
        best_score = score;
      }
    }
    taken[best] = true;
    picked.push_back(best);
  }
  for (std::size_t i : picked) chosen.push_back(corners[i]);
  return chosen;
}

}  // namespace tumble
