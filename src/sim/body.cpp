#include "tumble/body.hpp"

#include <cassert>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace tumble {

Vec3 box_inertia(double mass_kg, const Vec3& size) {
  const Vec3 s2 = size.cwiseProduct(size);
  return (mass_kg / 12.0) * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
}

std::vector<Vec3> box_corners(const Vec3& size) {
  const Vec3 h = 0.5 * size;
  std::vector<Vec3> corners;
  corners.reserve(8);
  for (int i = 0; i < 8; ++i)
    corners.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                         (i & 4) ? h.z() : -h.z());
  return corners;
}

std::vector<HullFace> box_faces() {
  // Corner index bits: 1 = +x, 2 = +y, 4 = +z.
  return {{-Vec3::UnitX(), {0, 4, 6, 2}}, {Vec3::UnitX(), {1, 3, 7, 5}},
          {-Vec3::UnitY(), {0, 1, 5, 4}}, {Vec3::UnitY(), {2, 6, 7, 3}},
          {-Vec3::UnitZ(), {0, 2, 3, 1}}, {Vec3::UnitZ(), {4, 5, 7, 6}}};
}

Vec3 sphere_inertia(double mass_kg, double radius_m) {
  return Vec3::Constant(0.4 * mass_kg * radius_m * radius_m);
}

std::vector<HullFace> faces_from_triangles(const std::vector<Vec3>& vertices,
                                           const std::vector<std::array<int, 3>>& triangles) {
  std::vector<HullFace> faces;
  std::vector<std::vector<int>> members;  // each face's vertices, unordered
  for (const auto& t : triangles) {
    const Vec3 n = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
    if (!(n.norm() > 0.0)) continue;
    const Vec3 u = n.normalized();
    std::size_t f = 0;
    while (f < faces.size() && (faces[f].normal - u).norm() > 1e-9) ++f;
    if (f == faces.size()) {
      faces.push_back({u, {}});
      members.emplace_back();
    }
    for (int v : t)
      if (std::find(members[f].begin(), members[f].end(), v) == members[f].end())
        members[f].push_back(v);
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    // Counter-clockwise about the outward normal: by angle around the centroid in the plane.
    const Vec3 n = faces[f].normal;
    Vec3 c = Vec3::Zero();
    for (int v : members[f]) c += vertices[v];
    c /= double(members[f].size());
    const Vec3 e1 = (vertices[members[f][0]] - c).normalized();
    const Vec3 e2 = n.cross(e1);
    std::vector<std::pair<double, int>> order;
    for (int v : members[f]) {
      const Vec3 d = vertices[v] - c;
      order.emplace_back(std::atan2(d.dot(e2), d.dot(e1)), v);
    }
    std::sort(order.begin(), order.end());
    for (const auto& [angle, v] : order) faces[f].vertices.push_back(v);
  }
  return faces;
}

namespace {

std::vector<Vec3> distinct_edge_directions(const std::vector<Vec3>& v,
                                           const std::vector<HullFace>& faces) {
  std::vector<Vec3> dirs;
  for (const HullFace& f : faces)
    for (std::size_t i = 0; i < f.vertices.size(); ++i) {
      Vec3 d = v[f.vertices[(i + 1) % f.vertices.size()]] - v[f.vertices[i]];
      if (!(d.norm() > 0.0)) continue;
      d.normalize();
      // One sign per direction: the first non-zero coordinate positive.
      const int k = std::abs(d.x()) > 1e-12 ? 0 : std::abs(d.y()) > 1e-12 ? 1 : 2;
      if (d(k) < 0.0) d = -d;
      bool known = false;
      for (const Vec3& e : dirs) known |= (e - d).norm() < 1e-9;
      if (!known) dirs.push_back(d);
    }
  return dirs;
}

Vec3 half_extent(const BodyDef& def) {
  if (def.particle) return Vec3::Zero();
  if (def.shape == ShapeKind::Sphere) return Vec3::Constant(def.radius_m);
  Vec3 h = Vec3::Zero();
  for (const Vec3& v : def.vertices) h = h.cwiseMax(v.cwiseAbs());
  return h;
}

double farthest(const BodyDef& def) {
  if (def.shape == ShapeKind::Sphere) return def.radius_m;
  double r = 0.0;
  for (const Vec3& v : def.vertices) r = std::max(r, v.norm());
  return r;
}

}  // namespace

std::shared_ptr<const RigidBody::Geometry> RigidBody::make_geometry(const BodyDef& def) {
  auto g = std::make_shared<Geometry>();
  // A box given by its 8 corners alone (tests, benchmarks) gets the faces they make.
  g->faces = def.faces.empty() && def.shape == ShapeKind::Box && def.vertices.size() == 8
                 ? box_faces()
                 : def.faces;
  g->edge_directions = distinct_edge_directions(def.vertices, g->faces);
  g->vertices = def.particle || def.shape == ShapeKind::Sphere ? std::vector<Vec3>{Vec3::Zero()}
                                                               : def.vertices;
  return g;
}

RigidBody::RigidBody(const BodyDef& def)
    : name_(def.name),
      particle_(def.particle),
      shape_(def.particle ? ShapeKind::Particle : def.shape),
      fixed_(def.fixed),
      radius_(def.radius_m),
      geometry_(make_geometry(def)),
      bounding_radius_(def.particle ? 0.0 : farthest(def)),
      half_extent_body_(half_extent(def)),
      mass_(def.mass_kg),
      inverse_mass_(def.fixed ? 0.0 : 1.0 / def.mass_kg),
      inertia_body_(def.particle ? Vec3(Vec3::Zero()) : def.inertia_body),
      inverse_inertia_body_(def.particle || def.fixed ? Vec3(Vec3::Zero())
                                                      : Vec3(def.inertia_body.cwiseInverse())),
      restitution_(def.restitution),
      principal_axes_(def.principal_axes.normalized()),
      com_offset_(def.com_offset),
      identity_axes_(def.principal_axes.coeffs() == Quat::Identity().coeffs()) {
  assert(def.mass_kg > 0.0);
  assert(def.particle || (def.inertia_body.array() > 0.0).all());
  state.x = def.position;
  state.P = fixed_ ? Vec3(Vec3::Zero()) : Vec3(mass_ * def.velocity);
  if (!particle_) {
    // The scene gives the model's orientation; the state carries the principal frame's.
    state.q = identity_axes_ ? def.orientation.normalized()
                             : Quat(def.orientation.normalized() * principal_axes_).normalized();
    state.R = state.q.toRotationMatrix();
    // L = I ω with the world inertia I = R I_body Rᵀ.
    if (!fixed_)
      state.L =
          state.R * inertia_body_.asDiagonal() * (state.R.transpose() * def.angular_velocity);
  }
}

Mat3 RigidBody::inverse_inertia_world() const {
  if (particle_) return Mat3::Zero();
  return state.R * inverse_inertia_body_.asDiagonal() * state.R.transpose();
}

namespace {
// Bitwise, not ==: -0 and +0 are different inputs to a renderer, and no pose is ever NaN.
template <typename M>
bool same_bits(const M& a, const M& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * std::size_t(a.size())) == 0;
}
}  // namespace

bool same_pose(const BodyState& a, const BodyState& b) {
  return same_bits(a.x, b.x) && same_bits(a.q.coeffs(), b.q.coeffs()) && same_bits(a.R, b.R);
}

double RigidBody::energy(const Vec3& gravity) const {
  if (fixed_) return 0.0;  // it never moves: its energy is no part of the run's
  return energy(gravity, particle_ ? Vec3(Vec3::Zero()) : angular_velocity());
}

double RigidBody::energy(const Vec3& gravity, const Vec3& omega) const {
  if (fixed_) return 0.0;
  const double linear = 0.5 * state.P.squaredNorm() * inverse_mass_;
  const double rotational = particle_ ? 0.0 : 0.5 * omega.dot(state.L);
  return linear + rotational - mass_ * gravity.dot(state.x);
}

}  // namespace tumble
