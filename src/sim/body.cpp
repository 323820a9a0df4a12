#include "tumble/body.hpp"

#include <cassert>
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

RigidBody::RigidBody(const BodyDef& def)
    : name_(def.name),
      particle_(def.particle),
      mass_(def.mass_kg),
      inverse_mass_(1.0 / def.mass_kg),
      inertia_body_(def.particle ? Vec3(Vec3::Zero()) : def.inertia_body),
      inverse_inertia_body_(def.particle ? Vec3(Vec3::Zero())
                                         : Vec3(def.inertia_body.cwiseInverse())),
      vertices_(def.particle ? std::vector<Vec3>{Vec3::Zero()} : def.vertices),
      restitution_(def.restitution),
      principal_axes_(def.principal_axes.normalized()),
      com_offset_(def.com_offset),
      identity_axes_(def.principal_axes.coeffs() == Quat::Identity().coeffs()) {
  assert(def.mass_kg > 0.0);
  assert(def.particle || (def.inertia_body.array() > 0.0).all());
  state.x = def.position;
  state.P = mass_ * def.velocity;
  if (!particle_) {
    // The scene gives the model's orientation; the state carries the principal frame's.
    state.q = identity_axes_ ? def.orientation.normalized()
                             : Quat(def.orientation.normalized() * principal_axes_).normalized();
    state.R = state.q.toRotationMatrix();
    // L = I ω with the world inertia I = R I_body Rᵀ.
    state.L = state.R * inertia_body_.asDiagonal() * (state.R.transpose() * def.angular_velocity);
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
  const double linear = 0.5 * state.P.squaredNorm() * inverse_mass_;
  const double rotational = particle_ ? 0.0 : 0.5 * angular_velocity().dot(state.L);
  return linear + rotational - mass_ * gravity.dot(state.x);
}

}  // namespace tumble
