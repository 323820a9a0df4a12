#pragma once
// A small linear complementarity problem: find f >= 0 with w = A f + b >= 0 and f·w = 0, for a
// symmetric positive semi-definite A of at most kMaxLcpSize rows (the contact points of one body
// on the floor). Solved exactly by trying active sets, largest first; each set is solved with a
// minimum-norm least-squares solve, so a symmetric problem (a box landing flat, whose 4 corner
// rows are linearly dependent) gets a symmetric answer.

#include <Eigen/Core>
#include <vector>

namespace tumble {

inline constexpr int kMaxLcpSize = 8;
using LcpMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLcpSize, kMaxLcpSize>;
using LcpVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLcpSize, 1>;

/// Returns f. Exact for n <= kMaxLcpSize when a solution exists (always, for PSD A coming from
/// contact); falls back to projected Gauss–Seidel in a fixed order if no active set verifies.
LcpVector solve_lcp(const LcpMatrix& A, const LcpVector& b);

/// The same problem of any size, for the contacts of an island of bodies: Dantzig's principal
/// pivoting as Baraff gives it ("Fast contact force computation for nonpenetrating rigid
/// bodies", 1994): each violated row is driven to complementarity in turn while the clamped set
/// keeps its rows at zero; clamped subsystems are solved for their minimum-norm solution, so
/// redundant contacts (a face resting on a face: 4 coplanar points) are taken as they come.
/// Starts from `active` (the clamped set of the last solve, warm start; may be empty) and
/// writes the final clamped set back. Returns false when it could not finish within its pivot
/// budget or A (with sliding friction, not symmetric) has no solution it can reach; `f` is then
/// the projected Gauss–Seidel answer, and the caller reports it. With `ridge_on_stall`, a
/// stalled solve is first retried with a diagonal of 1e-10 of A's largest added (see lcp.cpp).
/// Above this many rows a symmetric problem is solved iteratively (lcp.cpp: solve_large), to
/// the pivoting's tolerance where MPRGP reaches it within its iterations (false where not; the
/// answer it reached is kept); the pivots' dense subsystem solves cost minutes there. The size
/// where an island's held forces go sparse (held_rows.hpp: kSparseRows).
inline constexpr int kLargeLcpRows = 256;

/// Without `last_resort` a problem that no pivoting method solved is given up at once (f zero,
/// false): for a caller that discards that answer and solves another problem instead.
bool solve_lcp_pivoting(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
                        std::vector<char>& active, bool ridge_on_stall = false,
                        bool last_resort = true);

/// The same problem where f are impulses along contact normals and A their Delassus matrix (an
/// inelastic impact): the kinetic energy then changes by b·f + ½ fᵀA f, which a complementary f
/// makes −½ fᵀA f <= 0. Pivoting on dependent rows (four coplanar corners of a face) can end
/// off complementarity and push where a contact leaves, gaining energy; such an answer is
/// replaced by projected Gauss–Seidel from f = 0, each of whose steps minimises that energy
/// along one impulse, so it only dissipates. Returns false when the answer is that fallback
/// or `solve_lcp_pivoting`'s.
bool solve_lcp_dissipative(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
                           std::vector<char>& active, bool ridge_on_stall = false);

/// The minimum-norm least-squares solution of M x = rhs (M's pseudo-inverse times rhs) for a
/// symmetric positive semidefinite M: LDLᵀ with the largest diagonal of what is left pivoted
/// first, to rank r where that is no more than `threshold` of the first (and at least 1e-12 of
/// it: round-off of a singular pivot); then M⁺ through M = Pᵀ B D Bᵀ P (B = L's first r
/// columns). Measured on 240 rows, 0.3–2 ms where a complete orthogonal decomposition takes
/// 2.7–3.4 ms, the less the more rows depend on the others. False where M is not semidefinite
/// beyond round-off (x untouched).
bool least_norm_psd(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs, double threshold,
                    Eigen::VectorXd& x);

/// The minimum-norm least-squares solution of any square M x = rhs, ranks cut at `threshold` of
/// the largest: least_norm_psd where M is symmetric to 1e-12 of its largest entry (a contact
/// matrix, to round-off of its assembly; taken as its symmetric part), a complete orthogonal
/// decomposition otherwise (sliding friction's rows).
Eigen::VectorXd least_norm(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs, double threshold);

}  // namespace tumble
