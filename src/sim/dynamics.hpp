#pragma once
// The derivative dY/dt = (v, ½ ω⊗q or ω* R, F, τ) of one body, with the forces the scene models
// and, when the body has resting contacts, the floor's contact forces at those points.

#include <span>

#include "tumble/body.hpp"
#include "tumble/math.hpp"

namespace tumble {

struct ForceModel {
  Vec3 gravity{0.0, -9.81, 0.0};
  double linear_drag = 0.0;   // N·s/m, 0 = not computed
  double angular_drag = 0.0;  // N·m·s, 0 = not computed
  /// Solve every resting contact with the general LCP (the reference the fast face path is
  /// tested against), never with the resting-face wrench.
  bool general_contact_only = false;
};

/// dY/dt of one body; only the live orientation form (q or R) is filled.
struct Rate {
  Vec3 v;
  Vec4 qdot;  // (w, x, y, z) order, as Quat::coeffs() is not
  Mat3 Rdot;
  Vec3 F;
  Vec3 tau;
};

/// A set of a body's contact vertices (at most kMaxPoints) against the floor, e.g. the
/// resting contacts held during one stretch of a step.
struct ContactSet {
  /// A box has at most 4 points on a plane; a mesh hull's face is reduced to this many.
  static constexpr int kMaxPoints = 8;
  double floor_height = 0.0;
  int count = 0;
  int vertex[kMaxPoints] = {};
  /// Per point: slides with kinetic (Coulomb) friction inside the derivative. Points that do not
  /// slide get a sticking friction impulse after the stretch instead (see World).
  bool sliding[kMaxPoints] = {};
  double friction = 0.0;  ///< Coulomb mu of the floor
  std::span<const int> indices() const { return {vertex, static_cast<std::size_t>(count)}; }
};

/// The contact matrix A_ij = n·(n/m + (I⁻¹ (r_j × n)) × r_i) for the floor normal n = +y: the
/// normal velocity (or acceleration) change at point i per unit normal impulse (force) at j.
template <class Matrix>
void fill_contact_matrix(double inverse_mass, const Mat3& Iinv, const Vec3* r, int n, Matrix& A) {
  const Vec3 normal = Vec3::UnitY();
  A.resize(n, n);
  for (int j = 0; j < n; ++j) {
    const Vec3 dalpha = Iinv * r[j].cross(normal);
    for (int i = 0; i < n; ++i) A(i, j) = inverse_mass + normal.dot(dalpha.cross(r[i]));
  }
}

/// Orientation matrix of a (possibly mid-step, unnormalised) state.
Mat3 rotation_of(const BodyState& s, RotationRep rep);

class BodyDynamics {
 public:
  /// `evaluations`, when given, counts every evaluation of dY/dt (the work measure).
  BodyDynamics(const RigidBody& body, RotationRep rep, const ForceModel& forces,
               const ContactSet* resting, long* evaluations = nullptr)
      : body_(body), rep_(rep), forces_(forces), resting_(resting), evaluations_(evaluations) {}

  Rate operator()(const BodyState& s) const;
  /// The normal contact force at each resting point for state s (N), in resting-contact order.
  /// Empty when there are no resting contacts.
  void contact_forces(const BodyState& s, double* out) const;

  const RigidBody& body() const { return body_; }
  RotationRep rotation() const { return rep_; }

 private:
  // Free forces and torque at s, plus derived quantities reused by the contact solve.
  struct Kinematics {
    Mat3 R;
    Mat3 Iinv;
    Vec3 v, omega, F, tau;
  };
  Kinematics kinematics(const BodyState& s) const;
  void solve_contacts(const BodyState& s, const Kinematics& k, double* f) const;
  // The resting-face fast path: when >= 3 held points, frictionless or all sliding one way at one
  // height (a face sliding without turning), keep their normal accelerations at zero with a contact wrench whose centre of pressure lies inside their
  // support polygon, adds that wrench to k and returns true; else leaves k and returns false.
  bool add_face_wrench(const BodyState& s, Kinematics& k) const;
  Vec3 friction_direction(const Kinematics& k, const Vec3& r, int point) const;

  const RigidBody& body_;
  RotationRep rep_;
  const ForceModel& forces_;
  const ContactSet* resting_;
  long* evaluations_;
};

}  // namespace tumble
