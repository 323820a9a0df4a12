#include "integrators.hpp"

namespace tumble {
namespace {

// s + h·d over the state's live components (a particle has no orientation or L to advance).
BodyState add(const BodyState& s, const Rate& d, double h, const BodyDynamics& f) {
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

// Symplectic Euler: momenta first, then positions with the new velocities.
BodyState symplectic_euler(const BodyDynamics& f, const BodyState& s, double h) {
  const Rate d0 = f(s);
  BodyState kicked = s;
  kicked.P += h * d0.F;
  if (!f.body().is_particle()) kicked.L += h * d0.tau;
  const Rate d1 = f(kicked);  // v and ω from the new momenta at the old configuration
  BodyState out = kicked;
  out.x += h * d1.v;
  if (!f.body().is_particle()) {
    if (f.rotation() == RotationRep::Quaternion) {
      out.q.w() += h * d1.qdot(0);
      out.q.vec() += h * d1.qdot.tail<3>();
    } else {
      out.R += h * d1.Rdot;
    }
  }
  return out;
}

BodyState rk4(const BodyDynamics& f, const BodyState& s, double h) {
  const Rate k1 = f(s);
  const Rate k2 = f(add(s, k1, 0.5 * h, f));
  const Rate k3 = f(add(s, k2, 0.5 * h, f));
  const Rate k4 = f(add(s, k3, h, f));
  // Weighted sum written as successive adds, so the arithmetic is fixed and deterministic.
  BodyState out = add(s, k1, h / 6.0, f);
  out = add(out, k2, h / 3.0, f);
  out = add(out, k3, h / 3.0, f);
  return add(out, k4, h / 6.0, f);
}

// Symmetric orthonormalisation R (RᵀR)^(-1/2) by Newton–Schulz iterations: unlike Gram–Schmidt
// it favours no axis, and it converges quadratically from the small drift of one step.
Mat3 orthonormalize(const Mat3& R) {
  Mat3 X = R;
  for (int i = 0; i < 3; ++i) X = 1.5 * X - 0.5 * X * X.transpose() * X;
  return X;
}

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

BodyState integrate(const BodyDynamics& f, const BodyState& s, double h, Integrator method) {
  BodyState out;
  switch (method) {
    case Integrator::Euler:
      out = add(s, f(s), h, f);
      break;
    case Integrator::SymplecticEuler:
      out = symplectic_euler(f, s, h);
      break;
    case Integrator::Midpoint:
      out = add(s, f(add(s, f(s), 0.5 * h, f)), h, f);
      break;
    case Integrator::Rk4:
      out = rk4(f, s, h);
      break;
  }
  if (!f.body().is_particle()) normalize_orientation(out, f.rotation());
  return out;
}

}  // namespace tumble
