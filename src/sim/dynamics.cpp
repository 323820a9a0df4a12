#include "dynamics.hpp"

#include "lcp.hpp"

namespace tumble {

Mat3 rotation_of(const BodyState& s, RotationRep rep) {
  // Mid-step quaternions are not unit length; R is taken from the normalised one (Baraff).
  return rep == RotationRep::Quaternion ? s.q.normalized().toRotationMatrix() : s.R;
}

BodyDynamics::Kinematics BodyDynamics::kinematics(const BodyState& s) const {
  Kinematics k;
  k.v = s.P * body_.inverse_mass();
  k.F = body_.mass() * forces_.gravity;
  if (forces_.linear_drag > 0.0) k.F -= forces_.linear_drag * k.v;
  k.tau.setZero();
  if (body_.is_particle()) {
    k.R.setIdentity();
    k.Iinv.setZero();
    k.omega.setZero();
    return k;
  }
  k.R = rotation_of(s, rep_);
  k.Iinv = k.R * body_.inverse_inertia_body().asDiagonal() * k.R.transpose();
  k.omega = k.Iinv * s.L;
  if (forces_.angular_drag > 0.0) k.tau -= forces_.angular_drag * k.omega;
  return k;
}

void BodyDynamics::solve_contacts(const BodyState& s, const Kinematics& k, double* f) const {
  // Baraff, "Rigid Body Simulation II", resting contact: the normal acceleration of contact
  // point i is a_i = b_i + Σ_j A_ij f_j with f >= 0, a >= 0, f·a = 0.
  const auto idx = resting_->indices();
  const int n = resting_->count;
  const Vec3 normal = Vec3::UnitY();
  const double inv_m = body_.inverse_mass();
  const Vec3 a_cm = k.F * inv_m;
  // α = I⁻¹ (τ − ω × L): the derivative of ω = I⁻¹ L with I⁻¹ rotating along.
  const Vec3 alpha =
      body_.is_particle() ? Vec3::Zero() : Vec3(k.Iinv * (k.tau - k.omega.cross(s.L)));
  Vec3 r[8];
  for (Vec3& ri : r) ri.setZero();  // only the first n are used
  LcpVector b(n);
  for (int i = 0; i < n; ++i) {
    r[i] = k.R * body_.vertices()[idx[i]];
    b(i) = normal.dot(a_cm + alpha.cross(r[i]) + k.omega.cross(k.omega.cross(r[i])));
  }
  // Each point's force acts along n + d_j: d_j = −mu û_j for a sliding point (Coulomb kinetic
  // friction proportional to the normal force), 0 otherwise. A_ij is the normal acceleration at i
  // per unit normal force at j; with friction it is no longer symmetric (Baraff's dynamic
  // friction), which the active-set solver handles alike.
  LcpMatrix A(n, n);
  for (int j = 0; j < n; ++j) {
    const Vec3 e = normal + friction_direction(k, r[j], j);
    const Vec3 dalpha = k.Iinv * r[j].cross(e);
    for (int i = 0; i < n; ++i) A(i, j) = normal.dot(e * inv_m + dalpha.cross(r[i]));
  }
  const LcpVector sol = solve_lcp(A, b);
  for (int i = 0; i < n; ++i) f[i] = sol(i);
}

Vec3 BodyDynamics::friction_direction(const Kinematics& k, const Vec3& r, int point) const {
  if (!resting_->sliding[point] || resting_->friction <= 0.0) return Vec3::Zero();
  Vec3 slip = k.v + k.omega.cross(r);
  slip.y() = 0.0;
  const double speed = slip.norm();
  return speed > 0.0 ? Vec3(-resting_->friction / speed * slip) : Vec3::Zero();
}

void BodyDynamics::contact_forces(const BodyState& s, double* out) const {
  if (!resting_ || resting_->count == 0) return;
  solve_contacts(s, kinematics(s), out);
}

Rate BodyDynamics::operator()(const BodyState& s) const {
  if (evaluations_) ++*evaluations_;
  Kinematics k = kinematics(s);
  if (resting_ && resting_->count > 0) {
    double f[8];
    solve_contacts(s, k, f);
    const auto idx = resting_->indices();
    for (int i = 0; i < resting_->count; ++i) {
      const Vec3 r = k.R * body_.vertices()[idx[i]];
      const Vec3 force = f[i] * (Vec3::UnitY() + friction_direction(k, r, i));
      k.F += force;
      if (!body_.is_particle()) k.tau += r.cross(force);
    }
  }
  Rate d;
  d.v = k.v;
  d.F = k.F;
  d.tau = k.tau;
  if (body_.is_particle()) return d;
  if (rep_ == RotationRep::Quaternion) {
    // q̇ = ½ (0, ω) ⊗ q, written out in (w, x, y, z) order.
    const Vec3 qv = s.q.vec();
    const double qw = s.q.w();
    d.qdot(0) = -0.5 * k.omega.dot(qv);
    d.qdot.tail<3>() = 0.5 * (qw * k.omega + k.omega.cross(qv));
  } else {
    d.Rdot = star(k.omega) * s.R;  // the seed's R' = ω* R
  }
  return d;
}

}  // namespace tumble
