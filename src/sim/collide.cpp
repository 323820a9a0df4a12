#include "collide.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

#include "support_polygon.hpp"

namespace tumble {
namespace {

bool is_round(const RigidBody& b) {
  return b.shape() == ShapeKind::Sphere || b.shape() == ShapeKind::Particle;
}
double radius_of(const RigidBody& b) {
  return b.shape() == ShapeKind::Sphere ? b.radius() : 0.0;
}

// A body's vertices in the world. A box's eight are kept inline: the separating-axis test runs
// for every watched pair at every evaluation of an island's advancement (a third of a landing
// pile's time), and needs no heap allocation for each of its two bodies.
class WorldVertices {
 public:
  WorldVertices(const RigidBody& b, const Pose& p) : n_(b.vertices().size()) {
    if (n_ > kInline) heap_.resize(n_);
    Vec3* out = n_ > kInline ? heap_.data() : inline_.data();
    for (std::size_t i = 0; i < n_; ++i) out[i] = p.x + p.R * b.vertices()[i];
  }
  WorldVertices(const WorldVertices&) = delete;
  WorldVertices& operator=(const WorldVertices&) = delete;
  std::size_t size() const { return n_; }
  const Vec3& operator[](std::size_t i) const { return begin()[i]; }
  const Vec3* begin() const { return n_ > kInline ? heap_.data() : inline_.data(); }
  const Vec3* end() const { return begin() + n_; }

 private:
  static constexpr std::size_t kInline = 8;
  std::size_t n_;
  std::array<Vec3, kInline> inline_;
  std::vector<Vec3> heap_;
};

// The manifold with a and b exchanged: the normal reversed, each point's two ends swapped.
Manifold swapped(Manifold m) {
  m.normal = -m.normal;
  m.normal_of_b = !m.normal_of_b;
  std::swap(m.edge_a, m.edge_b);
  for (int i = 0; i < m.count; ++i) std::swap(m.points[i].on_a, m.points[i].on_b);
  return m;
}

// --- round shapes -------------------------------------------------------------------------

Manifold round_round(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                     double margin) {
  Manifold m;
  const Vec3 d = pb.x - pa.x;
  const double length = d.norm();
  // Concentric: any direction separates them equally; +y keeps it deterministic.
  m.normal = length > 0.0 ? Vec3(d / length) : Vec3(Vec3::UnitY());
  const double sep = length - radius_of(a) - radius_of(b);
  if (sep > margin) return m;
  m.count = 1;
  m.points[0] = {pa.x + radius_of(a) * m.normal, pb.x - radius_of(b) * m.normal, sep, 0};
  return m;
}

// The point of polyhedron h (world vertices w) closest to c, the signed distance of c from it
// (negative inside) and the outward unit normal there.
struct Closest {
  Vec3 point = Vec3::Zero();
  double distance = INFINITY;
  Vec3 normal = Vec3::UnitY();
  std::uint32_t feature = 0;
};

Vec3 closest_on_segment(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e = b - a;
  const double ee = e.squaredNorm();
  const double t = ee > 0.0 ? std::clamp((c - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return a + t * e;
}

Closest closest_on_polyhedron(const RigidBody& h, const Pose& p, const WorldVertices& w,
                              const Vec3& c) {
  const auto& faces = h.faces();
  // The deepest face plane: c is inside when every face plane has it behind.
  double deepest = -INFINITY;
  int deepest_face = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vec3 n = p.R * faces[f].normal;
    const double s = n.dot(c - w[faces[f].vertices[0]]);
    if (s > deepest) deepest = s, deepest_face = static_cast<int>(f);
  }
  Closest best;
  if (deepest <= 0.0) {
    best.normal = p.R * faces[deepest_face].normal;
    best.point = c - deepest * best.normal;
    best.distance = deepest;
    best.feature = static_cast<std::uint32_t>(deepest_face);
    return best;
  }
  // Outside: the closest point lies on a face that c is in front of, inside it or on its rim.
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vec3 n = p.R * faces[f].normal;
    const auto& v = faces[f].vertices;
    const double s = n.dot(c - w[v[0]]);
    if (s <= 0.0) continue;
    const Vec3 q = c - s * n;
    bool inside = true;
    for (std::size_t i = 0; i < v.size() && inside; ++i) {
      const Vec3& a = w[v[i]];
      const Vec3& b = w[v[(i + 1) % v.size()]];
      inside = (b - a).cross(n).dot(q - a) <= 0.0;
    }
    if (inside) {
      if (s < best.distance)
        best = {q, s, n, static_cast<std::uint32_t>(f)};
      continue;
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Vec3 e = closest_on_segment(w[v[i]], w[v[(i + 1) % v.size()]], c);
      const double d = (c - e).norm();
      if (d < best.distance)
        best = {e, d, d > 0.0 ? Vec3((c - e) / d) : n,
                static_cast<std::uint32_t>(0x10000u | (f << 8) | i)};
    }
  }
  return best;
}

// Round a against polyhedron b.
Manifold round_polyhedron(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                          double margin) {
  Manifold m;
  const Closest q = closest_on_polyhedron(b, pb, WorldVertices(b, pb), pa.x);
  // From a to b: against the outward normal of b where a's centre is.
  m.normal = -q.normal;
  m.normal_of_b = true;
  const double r = radius_of(a);
  const double sep = q.distance - r;
  if (sep > margin) return m;
  m.count = 1;
  m.points[0] = {pa.x + r * m.normal, q.point, sep, q.feature};
  return m;
}

// --- polyhedra: the separating-axis test ----------------------------------------------------

struct FaceQuery {
  int face = -1;
  double separation = -INFINITY;
};

// The face of `ref` whose plane has the incident body's vertices farthest in front of it.
FaceQuery query_faces(const RigidBody& ref, const Pose& pr, const WorldVertices& wr,
                      const WorldVertices& wi) {
  FaceQuery best;
  const auto& faces = ref.faces();
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vec3 n = pr.R * faces[f].normal;
    const double d = n.dot(wr[faces[f].vertices[0]]);
    double lowest = INFINITY;
    for (const Vec3& v : wi) lowest = std::min(lowest, n.dot(v));
    if (lowest - d > best.separation) best = {static_cast<int>(f), lowest - d};
  }
  return best;
}

struct EdgeQuery {
  int edge_a = -1, edge_b = -1;
  double separation = -INFINITY;
  Vec3 axis = Vec3::UnitY();
};

void project(const WorldVertices& w, const Vec3& axis, double& lo, double& hi) {
  lo = INFINITY, hi = -INFINITY;
  for (const Vec3& v : w) {
    const double d = axis.dot(v);
    lo = std::min(lo, d), hi = std::max(hi, d);
  }
}

// Every cross product of an edge direction of a with one of b, oriented from a to b: the
// separation of the projections of both bodies on it. Where only a separation of at least
// `floor` matters (the largest is all `separation()` takes), two boxes skip the axes that
// cannot reach it: a box's projection is its centre's ± Σ h_k |axis·u_k|, known without its
// vertices, to round-off (the margin: 1e-12 of the coordinates, far above it). What is found
// is the same axis and the same value, where it is at least `floor`.
EdgeQuery query_edges(const RigidBody& a, const Pose& pa, const WorldVertices& wa,
                      const RigidBody& b, const Pose& pb, const WorldVertices& wb,
                      double floor = -INFINITY) {
  EdgeQuery best;
  const bool boxes = floor > -INFINITY && a.shape() == ShapeKind::Box &&
                     b.shape() == ShapeKind::Box;
  const double margin = 1e-12 * (pa.x.cwiseAbs().maxCoeff() + pb.x.cwiseAbs().maxCoeff() +
                                 a.bounding_radius() + b.bounding_radius());
  const auto& da = a.edge_directions();
  const auto& db = b.edge_directions();
  // b's edge directions in the world, once where they are few (a box's three), not once per
  // edge of a.
  constexpr std::size_t kFew = 8;
  std::array<Vec3, kFew> eb_few;
  const bool few = db.size() <= kFew;
  if (few)
    for (std::size_t j = 0; j < db.size(); ++j) eb_few[j] = pb.R * db[j];
  for (std::size_t i = 0; i < da.size(); ++i) {
    const Vec3 ea = pa.R * da[i];
    for (std::size_t j = 0; j < db.size(); ++j) {
      Vec3 axis = ea.cross(few ? eb_few[j] : Vec3(pb.R * db[j]));
      const double length = axis.norm();
      // Edges parallel within 1e-6 rad: their cross product is a face normal's business.
      if (length < 1e-6) continue;
      axis /= length;
      if (axis.dot(pb.x - pa.x) < 0.0) axis = -axis;
      if (boxes) {
        const double reach_a = (pa.R.transpose() * axis).cwiseAbs().dot(a.half_extent_body());
        const double reach_b = (pb.R.transpose() * axis).cwiseAbs().dot(b.half_extent_body());
        if (axis.dot(pb.x - pa.x) - reach_a - reach_b + margin < std::max(floor, best.separation))
          continue;
      }
      double lo_a, hi_a, lo_b, hi_b;
      project(wa, axis, lo_a, hi_a);
      project(wb, axis, lo_b, hi_b);
      const double sep = lo_b - hi_a;
      if (sep > best.separation) best = {static_cast<int>(i), static_cast<int>(j), sep, axis};
    }
  }
  return best;
}

double polyhedra_separation(const RigidBody& a, const Pose& pa, const RigidBody& b,
                            const Pose& pb, Vec3* axis) {
  const WorldVertices wa(a, pa), wb(b, pb);
  const FaceQuery fa = query_faces(a, pa, wa, wb);
  const FaceQuery fb = query_faces(b, pb, wb, wa);
  // The edge axes only where a's faces do not already separate the two (every axis's gap is a
  // lower bound of the distance).
  const EdgeQuery ee = fa.separation > 0.0
                           ? EdgeQuery{}
                           : query_edges(a, pa, wa, b, pb, wb,
                                         std::max(fa.separation, fb.separation));
  const double best = std::max({fa.separation, fb.separation, ee.separation});
  if (axis) {
    if (best == fa.separation)
      *axis = pa.R * a.faces()[static_cast<std::size_t>(fa.face)].normal;
    else if (best == fb.separation)
      *axis = -(pb.R * b.faces()[static_cast<std::size_t>(fb.face)].normal);
    else
      *axis = ee.axis;
  }
  return best;
}

struct ClipPoint {
  Vec3 p;
  std::uint32_t feature;
};

// Keeps the part of `poly` with s·p <= offset (Sutherland–Hodgman against one plane).
void clip(std::vector<ClipPoint>& poly, const Vec3& s, double offset, std::uint32_t edge) {
  std::vector<ClipPoint> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ClipPoint& p = poly[i];
    const ClipPoint& q = poly[(i + 1) % n];
    const double dp = s.dot(p.p) - offset, dq = s.dot(q.p) - offset;
    if (dp <= 0.0) out.push_back(p);
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0))
      out.push_back({p.p + (dp / (dp - dq)) * (q.p - p.p), 0x20000u | (edge << 8) | p.feature});
  }
  poly.swap(out);
}

// Reduces more than Manifold::kMaxPoints points to the ones extreme in 8 directions of the
// reference plane (tangents t1, t2), which keeps their support polygon; deterministic.
void reduce(std::vector<ManifoldPoint>& points, const Vec3& t1, const Vec3& t2) {
  if (static_cast<int>(points.size()) <= Manifold::kMaxPoints) return;
  std::vector<PlanePoint> plane(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    plane[i] = {points[i].on_b.dot(t1), points[i].on_b.dot(t2), static_cast<int>(i)};
  std::vector<PlanePoint> hull(2 * plane.size() + 1);
  const int corners = support_polygon(plane.data(), static_cast<int>(plane.size()), hull.data());
  std::vector<int> keep;
  if (corners <= Manifold::kMaxPoints) {
    for (int c = 0; c < corners; ++c) keep.push_back(hull[c].index);
  } else {
    for (int d = 0; d < 8; ++d) {
      const double angle = d * (kPi / 4.0);
      const double cx = std::cos(angle), cz = std::sin(angle);
      const PlanePoint* best = &hull[0];
      for (int c = 0; c < corners; ++c)
        if (hull[c].x * cx + hull[c].z * cz > best->x * cx + best->z * cz) best = &hull[c];
      if (std::find(keep.begin(), keep.end(), best->index) == keep.end())
        keep.push_back(best->index);
    }
  }
  std::sort(keep.begin(), keep.end());
  std::vector<ManifoldPoint> kept;
  for (int i : keep) kept.push_back(points[i]);
  points.swap(kept);
}

// The reference face `face` of body r against body i (world vertices wr, wi): the incident face
// clipped by the reference face's sides; points within margin of the reference plane. The
// normal of the result points from r to i. `clipped`, where given, receives how many of its
// points are not the incident face's vertices but where the reference face's sides cut it.
Manifold face_contact(const RigidBody& r, const Pose& pr, const WorldVertices& wr, int face,
                      const RigidBody& in, const Pose& pi, const WorldVertices& wi,
                      double margin, int* clipped = nullptr) {
  const HullFace& ref = r.faces()[face];
  const Vec3 n = pr.R * ref.normal;
  // The incident face: the one of `in` most opposed to the reference normal.
  int incident = 0;
  double most = INFINITY;
  for (std::size_t f = 0; f < in.faces().size(); ++f) {
    const double d = (pi.R * in.faces()[f].normal).dot(n);
    if (d < most) most = d, incident = static_cast<int>(f);
  }
  std::vector<ClipPoint> poly;
  for (int v : in.faces()[incident].vertices) poly.push_back({wi[v], static_cast<std::uint32_t>(v)});
  const std::size_t k = ref.vertices.size();
  for (std::size_t e = 0; e < k && !poly.empty(); ++e) {
    const Vec3& a = wr[ref.vertices[e]];
    const Vec3& b = wr[ref.vertices[(e + 1) % k]];
    const Vec3 side = (b - a).cross(n);  // outward for a counter-clockwise face
    const double length = side.norm();
    if (!(length > 0.0)) continue;
    clip(poly, side / length, side.dot(a) / length, static_cast<std::uint32_t>(e));
  }
  const double offset = n.dot(wr[ref.vertices[0]]);
  std::vector<ManifoldPoint> points;
  if (clipped) *clipped = 0;
  for (const ClipPoint& c : poly) {
    const double sep = n.dot(c.p) - offset;
    if (sep > margin) continue;
    if (clipped && (c.feature & 0x20000u)) ++*clipped;
    const std::uint32_t feature =
        (static_cast<std::uint32_t>(face) << 24) | (static_cast<std::uint32_t>(incident) << 16) |
        (c.feature & 0xffffu);
    points.push_back({c.p - sep * n, c.p, sep, feature});
  }
  const Vec3 t1 = (wr[ref.vertices[1]] - wr[ref.vertices[0]]).normalized();
  reduce(points, t1, n.cross(t1));
  Manifold m;
  m.normal = n;
  for (const ManifoldPoint& p : points) m.points[m.count++] = p;
  return m;
}

// The edge of body b along direction `dir` (world) that is most extreme along `axis`.
void support_edge(const RigidBody& b, const WorldVertices& w, const Vec3& dir,
                  const Vec3& axis, Vec3& p0, Vec3& p1) {
  double best = -INFINITY;
  for (const HullFace& f : b.faces())
    for (std::size_t i = 0; i < f.vertices.size(); ++i) {
      const Vec3& a = w[f.vertices[i]];
      const Vec3& c = w[f.vertices[(i + 1) % f.vertices.size()]];
      const Vec3 e = c - a;
      if (std::abs(e.normalized().dot(dir)) < 1.0 - 1e-9) continue;
      const double d = axis.dot(a + c);
      if (d > best) best = d, p0 = a, p1 = c;
    }
}

// Closest points of segments p0p1 and q0q1 (Ericson, Real-Time Collision Detection, 5.1.9).
void closest_between_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                              Vec3& on_p, Vec3& on_q) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  double s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = e > 0.0 ? (b * s + f) / e : 0.0;
  if (t < 0.0) {
    t = 0.0;
    s = a > 0.0 ? std::clamp(-c / a, 0.0, 1.0) : 0.0;
  } else if (t > 1.0) {
    t = 1.0;
    s = a > 0.0 ? std::clamp((b - c) / a, 0.0, 1.0) : 0.0;
  }
  on_p = p0 + s * d1;
  on_q = q0 + t * d2;
}

Manifold polyhedra(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                   double margin) {
  Manifold none;
  const WorldVertices wa(a, pa), wb(b, pb);
  const FaceQuery fa = query_faces(a, pa, wa, wb);
  if (fa.separation > margin) return none;
  const FaceQuery fb = query_faces(b, pb, wb, wa);
  if (fb.separation > margin) return none;
  const EdgeQuery ee = query_edges(a, pa, wa, b, pb, wb);
  if (ee.separation > margin) return none;
  // Faces are preferred to edges, and a's face to b's (where they are one plane), unless
  // clearly worse (by 1e-3 of the smaller body's reach): a box resting face on face has edge
  // axes as good as its face axis, and a face gives the whole support polygon where an edge
  // gives one point.
  const double tol = 1e-3 * std::min(a.bounding_radius(), b.bounding_radius());
  const double face_best = std::max(fa.separation, fb.separation);
  const double edge_tol = 1e-9 * std::min(a.bounding_radius(), b.bounding_radius());
  auto edge_contact = [&] {
    Vec3 a0, a1, b0, b1, on_a, on_b;
    support_edge(a, wa, pa.R * a.edge_directions()[ee.edge_a], ee.axis, a0, a1);
    support_edge(b, wb, pb.R * b.edge_directions()[ee.edge_b], -ee.axis, b0, b1);
    closest_between_segments(a0, a1, b0, b1, on_a, on_b);
    Manifold m;
    m.normal = ee.axis;
    m.edges = true;
    m.edge_a = (a1 - a0).normalized();
    m.edge_b = (b1 - b0).normalized();
    m.count = 1;
    m.points[0] = {on_a, on_b, ee.separation,
                   0x40000000u | (static_cast<std::uint32_t>(ee.edge_a) << 8) |
                       static_cast<std::uint32_t>(ee.edge_b)};
    return m;
  };
  if (ee.edge_a >= 0 && ee.separation > face_best + edge_tol) return edge_contact();
  // The preference between a's face and b's only where they are the same plane, turned against
  // each other: faces of different directions (two boxes meeting edge to parallel edge) are
  // taken as the separating axes rank them.
  const Vec3 na = pa.R * a.faces()[static_cast<std::size_t>(fa.face)].normal;
  const Vec3 nb = pb.R * b.faces()[static_cast<std::size_t>(fb.face)].normal;
  const bool parallel = -na.dot(nb) > 1.0 - 1e-6;
  const double face_tol = parallel ? tol : edge_tol;
  int clipped_a = 0, clipped_b = 0;
  Manifold face = fb.separation > fa.separation + face_tol
                      ? swapped(face_contact(b, pb, wb, fb.face, a, pa, wa, margin, &clipped_b))
                      : face_contact(a, pa, wa, fa.face, b, pb, wb, margin, &clipped_a);
  // Two faces flat on each other touch at the corners of the region where both are: each a
  // vertex of one face inside the other, or where their sides cross. A point where the
  // reference face's side cuts the incident face is held as a point of the incident body, which
  // is right only at this instant: in a struck pyramid a box turning about the vertical swung
  // its face along its neighbour's at 1.1 m/s, past the neighbour's back corners, which lay
  // inside it. Held at the points of the swinging face where the neighbour's sides cut it, the
  // pair left the corners behind while they went on into the turning face (4e-5 m/s after
  // 16 µs): an impact every few microseconds, 173 in one step, and the pile's later steps went
  // 1e-6 m deep. Where the two faces are one plane (their separations within the preference),
  // the reference is the one whose sides cut fewer points: here the neighbour's corners on the
  // swinging face; a small box on a large one, its own corners on the large face.
  if (parallel && std::abs(fb.separation - fa.separation) <= face_tol) {
    const bool took_b = face.normal_of_b;
    const Manifold other = took_b ? face_contact(a, pa, wa, fa.face, b, pb, wb, margin, &clipped_a)
                                  : swapped(face_contact(b, pb, wb, fb.face, a, pa, wa, margin,
                                                         &clipped_b));
    const int here = took_b ? clipped_b : clipped_a, there = took_b ? clipped_a : clipped_b;
    if (other.count > 0 && (face.count == 0 || there < here)) face = other;
  }
  // A face within the preference of the edges whose clipped region is empty: two edges
  // crossing (two tilted dice meeting edge on), whose best axis is their cross product. The
  // face gave no point where the separating axes found the pair touching, and the pair went
  // on through itself unheld, every impact found on it empty.
  if (face.count == 0 && ee.edge_a >= 0 && ee.separation <= margin) return edge_contact();
  return face;
}

}  // namespace

double separation(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                  Vec3* axis) {
  if (is_round(a) && is_round(b)) {
    const Vec3 d = pb.x - pa.x;
    const double length = d.norm();
    if (axis) *axis = length > 0.0 ? Vec3(d / length) : Vec3(Vec3::UnitY());
    return length - radius_of(a) - radius_of(b);
  }
  if (is_round(a)) {
    const Closest q = closest_on_polyhedron(b, pb, WorldVertices(b, pb), pa.x);
    if (axis) *axis = -q.normal;
    return q.distance - radius_of(a);
  }
  if (is_round(b)) {
    const Closest q = closest_on_polyhedron(a, pa, WorldVertices(a, pa), pb.x);
    if (axis) *axis = q.normal;
    return q.distance - radius_of(b);
  }
  return polyhedra_separation(a, pa, b, pb, axis);
}

Manifold collide(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                 double margin) {
  if (is_round(a) && is_round(b)) return round_round(a, pa, b, pb, margin);
  if (is_round(a)) return round_polyhedron(a, pa, b, pb, margin);
  if (is_round(b)) return swapped(round_polyhedron(b, pb, a, pa, margin));
  return polyhedra(a, pa, b, pb, margin);
}

double plane_separation(double height, const RigidBody& b, const Pose& pb) {
  if (is_round(b)) return pb.x.y() - radius_of(b) - height;
  double lowest = INFINITY;
  for (const Vec3& v : b.vertices()) lowest = std::min(lowest, pb.x.y() + pb.R.row(1).dot(v));
  return lowest - height;
}

Manifold collide_plane(double height, const RigidBody& b, const Pose& pb, double margin) {
  Manifold m;
  m.normal = Vec3::UnitY();
  if (is_round(b)) {
    const Vec3 low = pb.x - radius_of(b) * Vec3::UnitY();
    const double sep = low.y() - height;
    if (sep > margin) return m;
    m.count = 1;
    m.points[0] = {Vec3(low.x(), height, low.z()), low, sep, 0};
    return m;
  }
  std::vector<ManifoldPoint> points;
  for (std::size_t i = 0; i < b.vertices().size(); ++i) {
    const Vec3 w = pb.x + pb.R * b.vertices()[i];
    const double sep = w.y() - height;
    if (sep <= margin)
      points.push_back({Vec3(w.x(), height, w.z()), w, sep, static_cast<std::uint32_t>(i)});
  }
  reduce(points, Vec3::UnitX(), Vec3::UnitZ());
  for (const ManifoldPoint& p : points) m.points[m.count++] = p;
  return m;
}

}  // namespace tumble
