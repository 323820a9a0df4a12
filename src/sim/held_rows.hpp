#pragma once
// The held contacts of an island as rows of one linear complementarity problem, and its sparse
// solve for islands too large for the dense one (island.cpp's IslandDynamics::solve).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "island.hpp"

namespace tumble {

/// Where a force along a contact acts on one side, and how its point moves.
struct SideGeometry {
  int member = -1;                  ///< local index, -1 for a static side
  Vec3 lever = Vec3::Zero();        ///< force lever from the centre of mass
  Vec3 point_lever = Vec3::Zero();  ///< lever of the constrained point (zero for a round side)
};

/// The frames of an island's held contacts at one state.
struct Frames {
  std::vector<ContactFrame> frame;
  std::vector<SideGeometry> a, b;
  std::vector<bool> round_pair;
};

/// A member's inverse mass and world inverse inertia at one state.
struct MassInfo {
  double inv_m;
  Mat3 Iinv;
};

/// The held-contact problem of an island at one state. Normal row i (one per contact): the
/// relative acceleration along n_i, w_i = (A x)_i + b_i, its force x_i >= 0 along dir_i (the
/// normal, less kinetic friction where the contact slides), complementary. Tangent rows (two per
/// sticking contact, along t[2j], t[2j+1] of contact sticking[j]): the tangential relative
/// acceleration of the contact's points, held at zero by free forces along the same tangents
/// while the contact presses (x > 0 or clamped), absent while it does not.
struct HeldRows {
  const Frames* f = nullptr;
  const std::vector<MassInfo>* m = nullptr;
  const std::vector<Vec3>* dir = nullptr;  ///< per contact, the normal row's force direction
  Eigen::VectorXd b;                       ///< per contact, the normal row's free acceleration
  std::vector<int> sticking;               ///< contacts with tangent rows, ascending
  std::vector<Vec3> t;                     ///< two unit tangents per sticking contact
  Eigen::VectorXd bt;                      ///< their free accelerations
};

/// What one sparse solve keeps for the next: the factorisation of its last symmetric guess,
/// reused where a later guess has the same rows less some (hold_or_slip frees sticking contacts
/// one at a time at one state). Whether it applies is checked row by row, to the bit.
class HeldRowsCache {
 public:
  HeldRowsCache();
  ~HeldRowsCache();
  struct Impl;
  std::unique_ptr<Impl> impl;
  /// The largest residual (relative to |b|) of an iterative answer taken since it was made:
  /// 0 where every answer was exact, or the iterations reached the pivots' tolerance.
  double iterative_residual = 0.0;

  /// Whether a problem with friction in it (its sticking contacts, and per contact whether it
  /// slides) was remembered as one no solve reached: a sticking contact that pulls when held
  /// and sinks when free has no answer in the modes fixed at the stretch's start, and
  /// hold_or_slip's rounds and the stretch's evaluations ask it again at nearby states, each
  /// time for every round of pivots in vain. The last four are remembered.
  bool unsettled(const std::vector<int>& sticking, const std::vector<char>& sliding) const;
  void remember_unsettled(const std::vector<int>& sticking, const std::vector<char>& sliding);

  /// The cache of one group of held contacts that share no body with the others (solved on
  /// its own: IslandDynamics::solve), by its contacts' (pair, feature): kept as long as this one.
  using GroupKey = std::vector<std::pair<int, std::uint32_t>>;
  HeldRowsCache& group(const GroupKey& key);

 private:
  std::vector<std::pair<std::vector<int>, std::vector<char>>> unsettled_;
  std::vector<std::pair<GroupKey, std::unique_ptr<HeldRowsCache>>> groups_;
};

/// Solves the held rows by block principal pivoting (Júdice and Pires) on sparse matrices,
/// begun from `active` (the clamped normal rows of the last solve, warm start) and written
/// back. Each guess is solved with a sparse factorisation of its rows with a diagonal of 1e-10
/// of the largest added (dependent rows, a face's four corners, then have one answer, near the
/// least-norm one, and a symmetric pose gets a symmetric split; the ridge moves the residual by
/// 1e-10 of |A| x, a tenth of the tolerance). The answer is accepted only where it is
/// complementary to the dense solve's tolerances: forces >= -1e-9 |b|/|A|, clamped rows within
/// 1e-6 |b| of zero, free rows >= -1e-9 |b|. False where the guesses do not settle within a few
/// rounds, a factorisation fails or the answer is not accepted: the caller then solves densely
/// (only where there is no friction in the matrix: beyond kSparseRows rows the dense pivots
/// take minutes, and the island takes its reported frictionless fallback). Where the pivots
/// do not settle from `active` and there are no tangent rows (and no sliding friction: A
/// symmetric), they start once more from the rows that press at the minimiser of the problem's
/// quadratic program, found by MPRGP (mprgp.hpp) to the same tolerance or 4 000 iterations;
/// where they do not settle from there either, that minimiser is the answer, and
/// `iterative_residual` (where given) its largest projected gradient relative to |b| (else 0).
/// A problem with tangent rows whose pivots did not settle is remembered in the cache (the
/// last four: their sticking contacts and sliding ones) and not tried again.
bool solve_held_rows_sparse(const HeldRows& rows, std::vector<char>& active,
                            Eigen::VectorXd& normal, Eigen::VectorXd& tangential,
                            HeldRowsCache* cache = nullptr,
                            double* iterative_residual = nullptr);

/// The least-norm solution (least squares where M x = rhs has none) of a symmetric positive
/// semidefinite M: the pivoted LDLᵀ (lcp.hpp: least_norm) up to kSparseRows rows; beyond, where
/// its cubic cost would dominate a large island's step, a sparse factorisation of M with a
/// diagonal of 1e-10 of its largest added (Tikhonov: the least-norm solution to about 1e-10
/// relative on consistent systems; a residual of 1e-10 |M| |x|), the dense one if that fails.
Eigen::VectorXd least_norm_solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs);

/// least_norm_solve of a block diagonal M, block by block (`group`: each row's block, from 0;
/// M's entries between blocks are not read): the same least-norm answer, to round-off, at the
/// cost of its blocks, not of the whole. A block with no row is skipped; one block is
/// least_norm_solve itself. At the impacts of a landing heap of a hundred dice, the friction's
/// dense solves over every touching contact of the island were a fifth of the run.
Eigen::VectorXd block_least_norm(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs,
                                 const std::vector<int>& group);

/// Above this many rows an island's contact problems are solved sparse first (held rows,
/// least_norm_solve); below it, dense. Both answers are exact, and give the same accelerations
/// (to 1e-9 of the largest, checked on every held-force solve of the dominoes scene to
/// 0.5875 s), but
/// where rows are dependent (a face's four corners, a domino's edge) the forces are not
/// unique: the dense pivots and the ridged sparse solve split them differently, by up to half
/// of the largest force. The split decides which sticking contacts hold_or_slip finds outside
/// their cones, so a chaotic scene takes another path: at 64 rows the twenty dominoes
/// diverged at 0.587 s and rocked in 1 813 micro-impacts in the next tenth (the dense solve:
/// 144). Below 256 rows the dense solve's cubic cost is affordable (the dominoes, ~100 rows:
/// 1.5 s simulated in 19 s); above, a woken pyramid (580 contacts) takes 0.5 s a step sparse
/// and 15–20 s dense.
inline constexpr int kSparseRows = 256;

}  // namespace tumble
