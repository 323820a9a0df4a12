#include "integrators.hpp"

#include "integrator_schemes.hpp"

#include <algorithm>
#include <cmath>

namespace tumble {

// Symmetric orthonormalisation R (RᵀR)^(-1/2) by Newton–Schulz iterations: unlike Gram–Schmidt
// it favours no axis, and it converges quadratically from the small drift of one step.
Mat3 orthonormalize(const Mat3& R) {
  Mat3 X = R;
  for (int i = 0; i < 3; ++i) X = 1.5 * X - 0.5 * X * X.transpose() * X;
  return X;
}

double orientation_drift(const BodyState& s, RotationRep rep) {
  if (rep == RotationRep::Quaternion) return std::abs(s.q.norm() - 1.0);
  return (s.R.transpose() * s.R - Mat3::Identity()).norm();
}

// The scaled error of a step: the largest of the position error against the body's length, the
// rotation error as an angle (radians), and the momentum errors against |P| + m·u and
// |L| + I·u/ℓ, divided by the tolerance. <= 1 means the step is accepted.
double body_scaled_error(const RigidBody& b, RotationRep rep, const BodyState& s, const Vec3& dx,
                         const Vec3& dP, const Vec3& dL, const Vec4& dq, const Mat3& dR,
                         const Stepping& how) {
  const double speed = how.speed_mps;
  double err = std::max(dx.norm() / how.length_m, dP.norm() / (s.P.norm() + b.mass() * speed));
  if (!b.is_particle()) {
    // A small change δq of a unit quaternion turns it by 2|δq|; a small δR by |δR|_F / √2.
    const double angle =
        rep == RotationRep::Quaternion ? 2.0 * dq.norm() : dR.norm() / std::sqrt(2.0);
    const double L_scale = b.inertia_body().maxCoeff() * speed / how.length_m;
    err = std::max({err, angle, dL.norm() / (s.L.norm() + L_scale)});
  }
  return err / how.tolerance;
}

namespace {

// One body as an integration system (integrator_schemes.hpp).
struct BodySystem {
  using State = BodyState;
  using Rates = Rate;
  struct ErrorSum {
    Vec3 dx = Vec3::Zero(), dP = Vec3::Zero(), dL = Vec3::Zero();
    Vec4 dq = Vec4::Zero();
    Mat3 dR = Mat3::Zero();
  };
  const BodyDynamics& f;

  Rate eval(const BodyState& s) const { return f(s); }
  // s + h·d over the state's live components (a particle has no orientation or L to advance).
  BodyState add(const BodyState& s, const Rate& d, double h) const {
    BodyState out = s;
    out.x += h * d.v;
    out.P += h * d.F;
    if (f.body().is_particle()) return out;
    out.L += h * d.tau;
    if (f.rotation() == RotationRep::Quaternion) {
      out.q.w() += h * d.qdot(0);
      out.q.vec() += h * d.qdot.tail<3>();
    } else {
      out.R += h * d.Rdot;
    }
    return out;
  }
  BodyState kick(const BodyState& s, const Rate& d, double h) const {
    BodyState out = s;
    out.P += h * d.F;
    if (!f.body().is_particle()) out.L += h * d.tau;
    return out;
  }
  BodyState drift(const BodyState& s, const Rate& d, double h) const {
    BodyState out = s;
    out.x += h * d.v;
    if (!f.body().is_particle()) {
      if (f.rotation() == RotationRep::Quaternion) {
        out.q.w() += h * d.qdot(0);
        out.q.vec() += h * d.qdot.tail<3>();
      } else {
        out.R += h * d.Rdot;
      }
    }
    return out;
  }
  ErrorSum error_sum() const { return {}; }
  void accumulate_error(ErrorSum& e, const Rate& k, double w) const {
    e.dx += w * k.v;
    e.dP += w * k.F;
    if (f.body().is_particle()) return;
    e.dL += w * k.tau;
    if (f.rotation() == RotationRep::Quaternion)
      e.dq += w * k.qdot;
    else
      e.dR += w * k.Rdot;
  }
  double scaled_error(const BodyState& s, const ErrorSum& e, const Stepping& how) const {
    return body_scaled_error(f.body(), f.rotation(), s, e.dx, e.dP, e.dL, e.dq, e.dR, how);
  }
  void finish(BodyState& s, StepInfo& info) const {
    if (f.body().is_particle()) return;
    info.orientation_drift = std::max(info.orientation_drift, orientation_drift(s, f.rotation()));
    normalize_orientation(s, f.rotation());
  }
};

}  // namespace

void normalize_orientation(BodyState& s, RotationRep rep) {
  if (rep == RotationRep::Quaternion) {
    s.q.normalize();
    s.R = s.q.toRotationMatrix();
  } else {
    s.R = orthonormalize(s.R);
    s.q = Quat(s.R).normalized();
  }
}

BodyState integrate(const BodyDynamics& f, const BodyState& s, double h, const Stepping& how,
                    StepInfo* info) {
  return schemes::step(BodySystem{f}, s, h, how, info);
}

}  // namespace tumble
