// Principal axes of an inertia tensor, chosen to stay as close to the file's axes as the
// physics allows: of all rotations whose columns are principal axes, the one nearest the
// identity (largest trace, since |R - 1|² = 6 - 2 tr R). Equal moments leave a whole subspace of
// principal axes; there the file's own axes (projected into it) are kept, so a cube, a sphere
// or a square plate is never turned by an arbitrary eigenvector basis.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

#include "tumble/mesh.hpp"

namespace tumble {
namespace {

// Moments closer than this, relative to the largest, are treated as equal. Models stored as
// float32 (every common format) carry ~1e-7 relative noise, so a sphere from a file is
// isotropic only to ~1e-7; treating moments within 1e-6 as equal changes the tensor by at
// most 1e-6 of its size, far below what any simulation here resolves.
constexpr double kEqualMoments = 1e-6;

// The rotation nearest the identity with column k = ±u and the other two spanning the plane
// orthogonal to u.
Mat3 nearest_rotation_with_axis(const Vec3& u, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;  // cyclic, so (c_i, c_j, c_k) right-handed
  Mat3 best = Mat3::Identity();
  double best_trace = -4.0;
  for (double sign : {1.0, -1.0}) {
    const Vec3 ck = sign * u;
    // In the plane: c_i = cos θ a + sin θ b, c_j = ck x c_i; maximise c_i.e_i + c_j.e_j =
    // A cos θ + B sin θ.
    Vec3 a = Vec3::Unit(i) - ck[i] * ck;
    if (a.norm() < 1e-12) a = Vec3::Unit(j) - ck[j] * ck;
    a.normalize();
    const Vec3 b = ck.cross(a);
    const double A = a[i] + b[j];  // from c_j = ck x c_i = cos θ b - sin θ a
    const double B = b[i] - a[j];
    const double theta = std::atan2(B, A);
    const Vec3 ci = std::cos(theta) * a + std::sin(theta) * b;
    Mat3 r;
    r.col(i) = ci;
    r.col(j) = ck.cross(ci);
    r.col(k) = ck;
    if (r.trace() > best_trace) {
      best_trace = r.trace();
      best = r;
    }
  }
  return best;
}

}  // namespace

PrincipalFrame principal_frame(const Mat3& inertia) {
  PrincipalFrame frame;
  const Mat3 symmetric = 0.5 * (inertia + inertia.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);
  const Vec3 lambda = solver.eigenvalues();  // ascending
  const Mat3 v = solver.eigenvectors();
  const double scale = std::max(std::abs(lambda[0]), std::abs(lambda[2]));
  const double tolerance = kEqualMoments * scale;
  const bool low_pair = lambda[1] - lambda[0] <= tolerance;
  const bool high_pair = lambda[2] - lambda[1] <= tolerance;

  if (solver.info() != Eigen::Success || !lambda.allFinite() || scale == 0.0 ||
      (low_pair && high_pair)) {
    // Isotropic (or nothing to decompose): every axis is principal; keep the file's.
    frame.axes = Mat3::Identity();
  } else if (low_pair || high_pair) {
    // One distinct moment: its axis is fixed, the other two free within the plane.
    const Vec3 u = v.col(low_pair ? 2 : 0);
    double best_trace = -4.0;
    for (int k = 0; k < 3; ++k) {
      const Mat3 r = nearest_rotation_with_axis(u, k);
      if (r.trace() > best_trace) {
        best_trace = r.trace();
        frame.axes = r;
      }
    }
  } else {
    // Distinct moments: the signed permutation of the eigenvectors nearest the identity.
    std::array<int, 3> p{0, 1, 2};
    double best_trace = -4.0;
    do {
      for (int signs = 0; signs < 8; ++signs) {
        Mat3 r;
        for (int c = 0; c < 3; ++c)
          r.col(c) = ((signs >> c) & 1 ? -1.0 : 1.0) * v.col(p[static_cast<std::size_t>(c)]);
        if (r.determinant() < 0.0) continue;
        if (r.trace() > best_trace) {
          best_trace = r.trace();
          frame.axes = r;
        }
      }
    } while (std::next_permutation(p.begin(), p.end()));
  }
  // The moment about each chosen axis (its Rayleigh quotient): exact for a distinct moment,
  // and within the tolerance above for equal ones, keeping the trace.
  for (int c = 0; c < 3; ++c)
    frame.moments[c] = frame.axes.col(c).dot(symmetric * frame.axes.col(c));
  return frame;
}

}  // namespace tumble
