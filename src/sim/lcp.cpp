#include "lcp.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace tumble {
namespace {

// Tolerance of the complementarity checks, relative to the problem's own scale: round-off in a
// least-squares solve of a well-scaled 8×8 system stays far below 1e-9 of it.
double tolerance(const LcpMatrix& A, const LcpVector& b) {
  const double scale = std::max(A.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return 1e-9 * std::max(scale, 1e-300);
}

bool try_active_set(const LcpMatrix& A, const LcpVector& b, unsigned mask, double tol,
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
  if (((As * fs - bs).cwiseAbs().array() > tol).any()) return false;
  if ((fs.array() < -tol).any()) return false;
  f.setZero(n);
  for (int r = 0; r < k; ++r) f(idx[r]) = std::max(fs(r), 0.0);
  const LcpVector w = A * f + b;
  for (int i = 0; i < n; ++i)
    if (!(mask & (1u << i)) && w(i) < -tol) return false;
  return true;
}

}  // namespace

LcpVector solve_lcp(const LcpMatrix& A, const LcpVector& b) {
  const int n = static_cast<int>(A.rows());
  assert(n == A.cols() && n == b.rows() && n <= kMaxLcpSize);
  LcpVector f = LcpVector::Zero(n);
  if (n == 0 || (b.array() >= 0.0).all()) return f;  // nothing pushes into the floor
  const double tol = tolerance(A, b);
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
