#include "lcp.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace tumble {
namespace {

// Tolerances of the complementarity checks, each in its own units so that no mass or length
// scale is preferred: residuals w = A f + b are compared with 1e-9 |b| (round-off in a
// least-squares solve of a small system stays far below it), forces f with that divided by |A|.
struct Tolerances {
  double w, f;
};
Tolerances tolerance(const LcpMatrix& A, const LcpVector& b) {
  const double w = 1e-9 * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  return {w, w / std::max(A.cwiseAbs().maxCoeff(), 1e-300)};
}

bool try_active_set(const LcpMatrix& A, const LcpVector& b, unsigned mask, const Tolerances& tol,
                    LcpVector& f) {
  const int n = static_cast<int>(A.rows());
  int idx[kMaxLcpSize];
  int k = 0;
  for (int i = 0; i < n; ++i)
    if (mask & (1u << i)) idx[k++] = i;
  LcpMatrix As(k, k);
  LcpVector bs(k);
  for (int r = 0; r < k; ++r) {
    bs(r) = -b(idx[r]);
    for (int c = 0; c < k; ++c) As(r, c) = A(idx[r], idx[c]);
  }
  const Eigen::CompleteOrthogonalDecomposition<LcpMatrix> cod(As);
  const LcpVector fs = cod.solve(bs);
  // A rank-deficient set may have no exact solution: check the residual, not just the signs.
  if (((As * fs - bs).cwiseAbs().array() > tol.w).any()) return false;
  if ((fs.array() < -tol.f).any()) return false;
  f.setZero(n);
  for (int r = 0; r < k; ++r) f(idx[r]) = std::max(fs(r), 0.0);
  const LcpVector w = A * f + b;
  for (int i = 0; i < n; ++i)
    if (!(mask & (1u << i)) && w(i) < -tol.w) return false;
  return true;
}

}  // namespace

LcpVector solve_lcp(const LcpMatrix& A, const LcpVector& b) {
  const int n = static_cast<int>(A.rows());
  assert(n == A.cols() && n == b.rows() && n <= kMaxLcpSize);
  LcpVector f = LcpVector::Zero(n);
  if (n == 0 || (b.array() >= 0.0).all()) return f;  // nothing pushes into the floor
  const Tolerances tol = tolerance(A, b);
  const unsigned all = (1u << n) - 1u;
  // Largest active sets first: a body pressed flat uses all its points (one solve).
  for (int size = n; size >= 1; --size)
    for (unsigned mask = 1; mask <= all; ++mask)
      if (std::popcount(mask) == size && try_active_set(A, b, mask, tol, f)) return f;
  // Not reached for PSD contact matrices; a deterministic fallback keeps the step going.
  f.setZero(n);
  for (int iter = 0; iter < 200; ++iter)
    for (int i = 0; i < n; ++i)
      if (A(i, i) > 0.0) f(i) = std::max(0.0, f(i) - (A.row(i).dot(f) + b(i)) / A(i, i));
  return f;
}

}  // namespace tumble
