#pragma once
// A small linear complementarity problem: find f >= 0 with w = A f + b >= 0 and f·w = 0, for a
// symmetric positive semi-definite A of at most kMaxLcpSize rows (the contact points of one body
// on the floor). Solved exactly by trying active sets, largest first; each set is solved with a
// minimum-norm least-squares solve, so a symmetric problem (a box landing flat, whose 4 corner
// rows are linearly dependent) gets a symmetric answer.

#include <Eigen/Core>

namespace tumble {

inline constexpr int kMaxLcpSize = 8;
using LcpMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLcpSize, kMaxLcpSize>;
using LcpVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLcpSize, 1>;

/// Returns f. Exact for n <= kMaxLcpSize when a solution exists (always, for PSD A coming from
/// contact); falls back to projected Gauss–Seidel in a fixed order if no active set verifies.
LcpVector solve_lcp(const LcpMatrix& A, const LcpVector& b);

}  // namespace tumble
