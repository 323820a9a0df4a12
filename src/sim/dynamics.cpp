#include "dynamics.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "lcp.hpp"
#include "support_polygon.hpp"

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
  // The constrained point of a sphere is its lowest point, which stays straight below the
  // centre however it turns: it moves with the centre (its lever is zero here), whereas a
  // material point of the rim would read a rolling ball's centripetal ω² r as lifting off.
  const bool round = body_.is_sphere();
  Vec3 p[8];
  for (int i = 0; i < n; ++i) {
    r[i] = body_.vertex_offset(k.R, idx[i]);
    p[i] = round ? Vec3(Vec3::Zero()) : r[i];
    b(i) = normal.dot(a_cm + alpha.cross(p[i]) + k.omega.cross(k.omega.cross(p[i])));
  }
  // Each point's force acts along n + d_j: d_j = −mu û_j for a sliding point (Coulomb kinetic
  // friction proportional to the normal force), 0 otherwise. A_ij is the normal acceleration at i
  // per unit normal force at j; with friction it is no longer symmetric (Baraff's dynamic
  // friction), which the active-set solver handles alike.
  LcpMatrix A(n, n);
  for (int j = 0; j < n; ++j) {
    const Vec3 e = normal + friction_direction(k, r[j], j);
    const Vec3 dalpha = k.Iinv * r[j].cross(e);
    for (int i = 0; i < n; ++i) A(i, j) = normal.dot(e * inv_m + dalpha.cross(p[i]));
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

namespace {

// The cofactor matrix of a symmetric 3×3 matrix (itself symmetric, and its adjugate).
Eigen::Matrix3d symmetric_cofactors(const Eigen::Matrix3d& a) {
  Eigen::Matrix3d c;
  c(0, 0) = a(1, 1) * a(2, 2) - a(1, 2) * a(1, 2);
  c(1, 1) = a(0, 0) * a(2, 2) - a(0, 2) * a(0, 2);
  c(2, 2) = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1);
  c(0, 1) = c(1, 0) = a(0, 2) * a(1, 2) - a(0, 1) * a(2, 2);
  c(0, 2) = c(2, 0) = a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1);
  c(1, 2) = c(2, 1) = a(0, 1) * a(0, 2) - a(0, 0) * a(1, 2);
  return c;
}

}  // namespace

bool BodyDynamics::add_face_wrench(const BodyState& s, Kinematics& k) const {
  // Without friction the motion depends on the contact forces only through their resultant
  // wrench — the force N along the normal n = +y at the centre of pressure p, i.e. F = N n and
  // τ = p × N n — which is unique when >= 3 non-collinear points hold, whereas the point forces
  // (what the LCP returns) are not. So instead of the 4-point LCP of a box on its face, a 3×3
  // solve. The same holds for a face that slides without turning: every point's force then acts
  // along the same e = n + d (d = −mu û, one slip direction û), so F = N e and τ = P × e with
  // P = Σ f_i r_i = (P_x, N r_y, P_z), the points being at one height r_y below the centre.
  const int n = resting_->count;
  if (n < 3 || body_.is_particle() || forces_.general_contact_only) return false;
  const auto idx = resting_->indices();
  Vec3 r[ContactSet::kMaxPoints];
  for (int i = 0; i < n; ++i) r[i] = body_.vertex_offset(k.R, idx[i]);
  Vec3 d = Vec3::Zero();
  if (resting_->friction > 0.0 && resting_->sliding[0]) {
    // One slip direction and one height, to 1e-12 (of mu, of the body's extent): closer than
    // the LCP's own round-off-level tolerances, so its solution is this one.
    d = friction_direction(k, r[0], 0);
    double reach = 0.0;
    for (int i = 0; i < n; ++i) reach = std::max(reach, r[i].norm());
    for (int i = 1; i < n; ++i)
      if (!resting_->sliding[i] ||
          (friction_direction(k, r[i], i) - d).cwiseAbs().maxCoeff() > 1e-12 * resting_->friction ||
          std::abs(r[i].y() - r[0].y()) > 1e-12 * reach)
        return false;
  } else if (resting_->friction > 0.0) {
    for (int i = 0; i < n; ++i)
      if (resting_->sliding[i]) return false;  // some slide, some stick: the LCP
  }
  const double inv_m = body_.inverse_mass();
  const Vec3 a_cm = k.F * inv_m;
  const Vec3 alpha = k.Iinv * (k.tau - k.omega.cross(s.L));
  const Mat3& G = k.Iinv;
  // Unknowns w = (N, P_x, P_z); the contact torque is τ = T w with, for e = (d_x, 1, d_z),
  // τ_x = N r_y d_z − P_z, τ_y = P_z d_x − P_x d_z, τ_z = P_x − N r_y d_x.
  const double ry = r[0].y();
  Eigen::Matrix3d T;
  T << ry * d.z(), 0.0, -1.0,  //
      0.0, -d.z(), d.x(),      //
      -ry * d.x(), 1.0, 0.0;
  // Without friction (d = 0) T's products are written out: GT = (0, G e_z, −G e_x) and
  // τ = (−P_z, 0, P_x), the same values as the general products (their other terms are zeros),
  // without the 3×3 product in every derivative evaluation. (Awake contact on a frictionless
  // face had slowed from 0.73–0.76 M rk4 steps/s to 0.64–0.66 M since friction came here; with
  // this and the scalar sums below, 10–16 % of that back, same bytes.)
  const bool plain = d == Vec3::Zero();
  const Eigen::Matrix3d GT = plain ? Eigen::Matrix3d::Zero() : Eigen::Matrix3d(G * T);
  // Normal acceleration of point i: b_i + J_i · w, J_i = (1/m, 0, 0) + r_ix (GT)_z − r_iz (GT)_x
  // (the y component of α × r_i is α_z r_x − α_x r_z; friction moves the centre sideways only).
  // JᵀJ and Jᵀb summed entry by entry in scalars (JᵀJ's upper triangle, mirrored: J_a J_b is
  // J_b J_a): the same sums as adding J Jᵀ point by point, without a 3×3 temporary on the
  // stack per point, whose reloads stalled on its stores (a third of this function's time).
  double s00 = 0.0, s01 = 0.0, s02 = 0.0, s11 = 0.0, s12 = 0.0, s22 = 0.0;
  double t0 = 0.0, t1 = 0.0, t2 = 0.0;
  double extent = 0.0;
  for (int i = 0; i < n; ++i) {
    extent = std::max({extent, std::abs(r[i].x()), std::abs(r[i].z())});
    const double b = a_cm.y() + alpha.cross(r[i]).y() + k.omega.cross(k.omega.cross(r[i])).y();
    const Vec3 J =
        plain ? Vec3(inv_m, r[i].x() * G(2, 2) - r[i].z() * G(0, 2),
                     r[i].x() * -G(2, 0) - r[i].z() * -G(0, 0))
              : Vec3(Vec3(inv_m, 0.0, 0.0) +
                     (r[i].x() * GT.row(2) - r[i].z() * GT.row(0)).transpose());
    s00 += J(0) * J(0), s01 += J(0) * J(1), s02 += J(0) * J(2);
    s11 += J(1) * J(1), s12 += J(1) * J(2), s22 += J(2) * J(2);
    t0 += J(0) * b, t1 += J(1) * b, t2 += J(2) * b;
  }
  Eigen::Matrix3d JtJ;
  JtJ << s00, s01, s02,  //
      s01, s11, s12,     //
      s02, s12, s22;
  const Vec3 Jtb(t0, t1, t2);
  // Least squares: the points are coplanar (they all touch the plane), so the system is
  // consistent and this is its exact solution; collinear points make JtJ singular: not a face.
  // Solved in closed form (cofactors; JtJ is symmetric): for a 3×3 in every derivative
  // evaluation a factorisation costs more than the solve. det / (product of the diagonal) is in
  // [0, 1] for a positive semi-definite matrix (Hadamard) and ~1e-16 for collinear points: below
  // 1e-12 the face is left to the LCP, which is always right (this path is only a shortcut).
  const Eigen::Matrix3d C = symmetric_cofactors(JtJ);
  const double det = JtJ.row(0).dot(C.row(0));
  if (!(det > 1e-12 * JtJ(0, 0) * JtJ(1, 1) * JtJ(2, 2))) return false;
  const Vec3 w = C * (-Jtb) / det;  // C is symmetric: the adjugate
  const double N = w(0);
  if (!(N > 0.0)) return false;  // the floor cannot pull: the body leaves it (the LCP decides)
  // Centre of pressure (relative to the centre of mass, in the floor plane) strictly inside the
  // points' convex hull, by a margin of 1e-9 of their extent: then non-negative point forces
  // realise the wrench and every point's acceleration is zero — the LCP's solution. On or
  // outside an edge the body tips: the general LCP decides which points stay.
  const double cx = w(1) / N, cz = w(2) / N;
  PlanePoint points[ContactSet::kMaxPoints], hull[2 * ContactSet::kMaxPoints + 1];
  for (int i = 0; i < n; ++i) points[i] = {r[i].x(), r[i].z(), i};
  if (!strictly_inside(hull, support_polygon(points, n, hull), cx, cz, 1e-9 * extent)) return false;
  if (plain) {
    k.F.y() += N;
    k.tau.x() += -w(2);
    k.tau.z() += w(1);
    return true;
  }
  k.F += N * (Vec3::UnitY() + d);
  k.tau += T * w;
  return true;
}

Rate BodyDynamics::operator()(const BodyState& s) const {
  if (evaluations_) ++*evaluations_;
  Kinematics k = kinematics(s);
  if (resting_ && resting_->count > 0 && !add_face_wrench(s, k)) {
    double f[8];
    solve_contacts(s, k, f);
    const auto idx = resting_->indices();
    for (int i = 0; i < resting_->count; ++i) {
      const Vec3 r = body_.vertex_offset(k.R, idx[i]);
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
