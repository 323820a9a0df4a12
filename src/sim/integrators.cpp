#include "integrators.hpp"

#include <algorithm>
#include <cmath>

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

double orientation_drift(const BodyState& s, RotationRep rep) {
  if (rep == RotationRep::Quaternion) return std::abs(s.q.norm() - 1.0);
  return (s.R.transpose() * s.R - Mat3::Identity()).norm();
}

// Dormand & Prince, "A family of embedded Runge-Kutta formulae" (1980): the 5th-order solution
// is propagated, the embedded 4th-order one only estimates the error; FSAL (the last stage is the
// next step's first).
constexpr double kA[7][6] = {
    {},
    {1.0 / 5.0},
    {3.0 / 40.0, 9.0 / 40.0},
    {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
    {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
    {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
    {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0}};
// b (5th order) − b* (4th order): the error estimate's weights.
constexpr double kE[7] = {71.0 / 57600.0,      0.0,          -71.0 / 16695.0, 71.0 / 1920.0,
                          -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};

// s + h Σ_j w_j k_j, as successive adds in a fixed order (deterministic arithmetic).
BodyState combine(const BodyState& s, const Rate* k, const double* w, int n, double h,
                  const BodyDynamics& f) {
  BodyState out = s;
  for (int j = 0; j < n; ++j)
    if (w[j] != 0.0) out = add(out, k[j], h * w[j], f);
  return out;
}

// The scaled error of a step: the largest of the position error against the body's length, the
// rotation error as an angle (radians), and the momentum errors against |P| + m·u and
// |L| + I·u/ℓ, divided by the tolerance. <= 1 means the step is accepted.
double scaled_error(const BodyState& s, const Rate* k, double h, const BodyDynamics& f,
                    const Stepping& how) {
  const RigidBody& b = f.body();
  Vec3 dx = Vec3::Zero(), dP = Vec3::Zero(), dL = Vec3::Zero();
  Vec4 dq = Vec4::Zero();
  Mat3 dR = Mat3::Zero();
  for (int j = 0; j < 7; ++j) {
    if (kE[j] == 0.0) continue;
    dx += (h * kE[j]) * k[j].v;
    dP += (h * kE[j]) * k[j].F;
    if (b.is_particle()) continue;
    dL += (h * kE[j]) * k[j].tau;
    if (f.rotation() == RotationRep::Quaternion)
      dq += (h * kE[j]) * k[j].qdot;
    else
      dR += (h * kE[j]) * k[j].Rdot;
  }
  const double speed = how.speed_mps;
  double err = std::max(dx.norm() / how.length_m, dP.norm() / (s.P.norm() + b.mass() * speed));
  if (!b.is_particle()) {
    // A small change δq of a unit quaternion turns it by 2|δq|; a small δR by |δR|_F / √2.
    const double angle =
        f.rotation() == RotationRep::Quaternion ? 2.0 * dq.norm() : dR.norm() / std::sqrt(2.0);
    const double L_scale = b.inertia_body().maxCoeff() * speed / how.length_m;
    err = std::max({err, angle, dL.norm() / (s.L.norm() + L_scale)});
  }
  return err / how.tolerance;
}

// Covers h in substeps of Dormand–Prince 5(4) with Hairer's PI controller (DOPRI5: β = 0.04,
// exponent 1/5 − 0.75β, safety 0.9, step ratio in [0.2, 10]).
BodyState dormand_prince(const BodyDynamics& f, const BodyState& s0, double h, const Stepping& how,
                         StepInfo& info) {
  constexpr double kBeta = 0.04, kExpo = 0.2 - 0.75 * kBeta, kSafe = 0.9;
  constexpr double kMinRatio = 0.2, kMaxRatio = 10.0;
  AdaptiveController c = how.controller;
  BodyState s = s0;
  double t = 0.0;
  // The controller's wish; a substep is the wish, or what is left of the stretch when that is
  // (a hair more than) less.
  double wish = c.h_next_s > 0.0 ? c.h_next_s : h;
  Rate k[7];
  k[0] = f(s);
  while (t < h) {
    const bool last = h - t <= wish * (1.0 + 1e-9);
    const double hs = last ? h - t : wish;
    for (int i = 1; i < 7; ++i) k[i] = f(combine(s, k, kA[i], i, hs, f));
    const double err = scaled_error(s, k, hs, f, how);
    const bool finite = std::isfinite(err);
    const bool at_floor = hs <= how.min_step_s;
    if ((finite && err <= 1.0) || at_floor) {
      // Pinned: the controller was held at its floor with the error above tolerance (not a
      // stretch end shorter than the floor, which an impact can leave: femtoseconds).
      const bool whole = hs >= wish * (1.0 - 1e-9);
      if (at_floor && whole && !(err <= 1.0)) info.pinned = true;
      s = combine(s, k, kA[6], 6, hs, f);
      t = last ? h : t + hs;
      ++info.accepted;
      // Step statistics are the controller's choices, not substeps cut short by the stretch.
      if (whole) {
        info.smallest_step_s =
            info.smallest_step_s == 0.0 ? hs : std::min(info.smallest_step_s, hs);
        info.largest_step_s = std::max(info.largest_step_s, hs);
      }
      const double e = finite ? std::max(err, 1e-4) : 1.0;
      double ratio = std::pow(e, kExpo) / std::pow(c.err_prev, kBeta) / kSafe;
      ratio = std::clamp(ratio, 1.0 / kMaxRatio, 1.0 / kMinRatio);
      c.err_prev = e;
      const double proposal = std::max(hs / ratio, how.min_step_s);
      // A substep shortened to end the stretch says little about the next one's size.
      c.h_next_s = whole ? proposal : std::max(proposal, wish);
      wish = c.h_next_s;
      k[0] = k[6];  // FSAL: the last stage was evaluated at the new state
    } else {
      ++info.rejected;
      const double shrink =
          finite ? std::clamp(std::pow(err, kExpo) / kSafe, 1.0, 1.0 / kMinRatio) : 1.0 / kMinRatio;
      wish = std::max(hs / shrink, how.min_step_s);
    }
  }
  info.controller = c;
  return s;
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

BodyState integrate(const BodyDynamics& f, const BodyState& s, double h, const Stepping& how,
                    StepInfo* info) {
  StepInfo local;
  StepInfo& out_info = info ? *info : local;
  out_info = StepInfo{};
  out_info.controller = how.controller;
  BodyState out;
  switch (how.method) {
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
    case Integrator::Adaptive:
      out = dormand_prince(f, s, h, how, out_info);
      break;
  }
  if (!f.body().is_particle()) {
    out_info.orientation_drift = orientation_drift(out, f.rotation());
    normalize_orientation(out, f.rotation());
  }
  return out;
}

}  // namespace tumble
