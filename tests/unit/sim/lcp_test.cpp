#include "../../../src/sim/lcp.hpp"
#include "../../../src/sim/mprgp.hpp"

#include <Eigen/QR>
#include <gtest/gtest.h>

#include <random>

namespace tumble {
namespace {

// Checks f >= 0, w = A f + b >= 0 and f·w = 0, each to 1e-9 of the problem's scale.
void expect_complementary(const LcpMatrix& A, const LcpVector& b, const LcpVector& f) {
  const LcpVector w = A * f + b;
  const double tol = 1e-9 * std::max(1.0, b.cwiseAbs().maxCoeff());
  for (int i = 0; i < f.size(); ++i) {
    EXPECT_GE(f(i), -tol);
    EXPECT_GE(w(i), -tol);
    EXPECT_LT(std::abs(f(i) * w(i)), tol * std::max(1.0, std::abs(f(i))));
  }
}

TEST(Lcp, FourCoplanarPointsGetEqualForces) {
  // A unit box resting flat: rows are linearly dependent (rank 3), the min-norm answer is
  // symmetric: m g / 4 at each corner.
  const double m = 1.0, I = m / 6.0, g = 9.81;
  const double r[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};  // (x, z)
  LcpMatrix A(4, 4);
  LcpVector b(4);
  for (int i = 0; i < 4; ++i) {
    b(i) = -g;
    for (int j = 0; j < 4; ++j) A(i, j) = 1.0 / m + (r[i][0] * r[j][0] + r[i][1] * r[j][1]) / I;
  }
  const LcpVector f = solve_lcp(A, b);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(f(i), m * g / 4.0, 1e-12);
  expect_complementary(A, b, f);
}

TEST(Lcp, SeparatingPointsGetNoForce) {
  LcpMatrix A(2, 2);
  A << 2.0, 1.0, 1.0, 2.0;
  LcpVector b(2);
  b << -1.0, 3.0;
  const LcpVector f = solve_lcp(A, b);
  EXPECT_NEAR(f(0), 0.5, 1e-12);
  EXPECT_EQ(f(1), 0.0);
  expect_complementary(A, b, f);
}

TEST(Lcp, RandomPsdProblemsAreSolvedExactly) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % kMaxLcpSize;
    const int rank = 1 + trial % 3 + (trial % 2) * 3;  // contact matrices have rank <= 6
    Eigen::MatrixXd J = Eigen::MatrixXd::NullaryExpr(n, rank, [&] { return normal(rng); });
    LcpMatrix A = J * J.transpose() + 1e-3 * Eigen::MatrixXd::Identity(n, n);
    LcpVector b = LcpVector::NullaryExpr(n, [&] { return normal(rng); });
    expect_complementary(A, b, solve_lcp(A, b));
  }
}

TEST(LcpPivoting, SolvesAnUnsymmetricProblemPrincipalPivotingCannot) {
  // A sliding-friction matrix J M⁻¹ (J − mu T)ᵀ (found by a random search, rounded to quarters)
  // on which Dantzig's principal pivoting finds its step unbounded; Lemke's method reaches the
  // solution, exact in quarters: f = (0.4, 1.8, 0.2, 0), w = (0, 0, 0, 1.15).
  Eigen::MatrixXd A(4, 4);
  A << 1.25, 0.0, 1.25, 0.0,  //
      -1.5, 1.0, -1.0, 0.5,   //
      1.5, -0.75, 1.25, 0.0,  //
      0.75, 0.0, 0.5, 0.75;
  Eigen::VectorXd b(4);
  b << -0.75, -1.0, 0.5, 0.75;
  Eigen::VectorXd f;
  std::vector<char> active;
  ASSERT_TRUE(solve_lcp_pivoting(A, b, f, active));
  const Eigen::VectorXd expected = (Eigen::VectorXd(4) << 0.4, 1.8, 0.2, 0.0).finished();
  EXPECT_LT((f - expected).cwiseAbs().maxCoeff(), 1e-12);  // a 4x4 solve: round-off only
  const Eigen::VectorXd w = A * f + b;
  EXPECT_NEAR(w(3), 1.15, 1e-12);
  // The clamped set it found warm-starts the next solve, which then needs no pivot.
  EXPECT_EQ(active, (std::vector<char>{1, 1, 1, 0}));
  Eigen::VectorXd again;
  ASSERT_TRUE(solve_lcp_pivoting(A, b, again, active));
  EXPECT_LT((again - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(LcpPivoting, AProblemWithoutSolutionGetsGaussSeidelOnlyAsALastResort) {
  // w1 = f1 − f2 − 1 and w2 = f2 − f1 − 1 cannot both be >= 0 (their sum is −2): no pivoting
  // finds a solution. By default the answer is projected Gauss–Seidel's, and false; a caller
  // that will solve another problem instead (an island's held forces, again without their
  // sliding friction) asks for no last resort and gets no force, and false, at once.
  Eigen::MatrixXd A(2, 2);
  A << 1.0, -1.0,  //
      -1.0, 1.0;
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(2, -1.0);
  Eigen::VectorXd f;
  std::vector<char> active;
  EXPECT_FALSE(solve_lcp_pivoting(A, b, f, active));
  EXPECT_GT(f.cwiseAbs().maxCoeff(), 0.0);  // Gauss–Seidel's sweeps moved it
  EXPECT_EQ(active, (std::vector<char>{0, 0}));
  Eigen::VectorXd none;
  EXPECT_FALSE(solve_lcp_pivoting(A, b, none, active, false, /*last_resort=*/false));
  EXPECT_EQ(none, Eigen::VectorXd::Zero(2));
  EXPECT_EQ(active, (std::vector<char>{0, 0}));
}

TEST(LcpPivoting, RowsThatASymmetricPoseMakesEqualChangeTogether) {
  // Rows 0 and 1 are the two ends of an edge in a symmetric pose (equal rows, swapped), with
  // sliding friction's coupling making A not a P-matrix: the LCP then has a lopsided answer,
  // (1, 0, 0), as well as the symmetric one, (1/3, 1/3, 0). The warm start (only row 2 was
  // clamped) fails; Dantzig's method from f = 0 drives row 0 first, which lifts row 1 off, and
  // ends lopsided, turning a planar scene out of its plane. Block pivoting changes both ends
  // together. Exact in thirds.
  Eigen::MatrixXd A(3, 3);
  A << 1.0, 2.0, 0.0,  //
      2.0, 1.0, 0.0,   //
      0.0, 0.0, 1.0;
  Eigen::VectorXd b(3);
  b << -1.0, -1.0, 1.0;
  Eigen::VectorXd f;
  std::vector<char> active{0, 0, 1};
  ASSERT_TRUE(solve_lcp_pivoting(A, b, f, active));
  const Eigen::VectorXd expected = (Eigen::VectorXd(3) << 1.0 / 3.0, 1.0 / 3.0, 0.0).finished();
  EXPECT_LT((f - expected).cwiseAbs().maxCoeff(), 1e-15);  // a 2x2 solve: round-off only
  EXPECT_NEAR(f(0), f(1), 1e-15);
  const Eigen::VectorXd w = A * f + b;
  EXPECT_NEAR(w(2), 1.0, 1e-15);
  EXPECT_EQ(active, (std::vector<char>{1, 1, 0}));
}

TEST(LcpPivoting, AnEdgeHeldByOneEndOfTwoIsSplitEvenly) {
  // Rows 0 and 1 are the two ends of a symmetric edge pressed onto a face (equal rows: A is
  // singular), row 2 a point that separates. f = (1, 0, 0) is a solution — the end left free
  // has w = 0 — and so is every split with f0 + f1 = 1. The warm start (only row 0 clamped)
  // ends on the lopsided one; the answer kept is the minimum-norm split over the rows at
  // w = 0, which the symmetry makes even. Exact in halves.
  Eigen::MatrixXd A(3, 3);
  A << 1.0, 1.0, 0.5,  //
      1.0, 1.0, 0.5,   //
      0.5, 0.5, 2.0;
  Eigen::VectorXd b(3);
  b << -1.0, -1.0, 1.0;
  Eigen::VectorXd f;
  std::vector<char> active{1, 0, 0};
  ASSERT_TRUE(solve_lcp_pivoting(A, b, f, active));
  EXPECT_NEAR(f(0), 0.5, 1e-15);
  EXPECT_NEAR(f(1), 0.5, 1e-15);
  EXPECT_EQ(f(2), 0.0);
  const Eigen::VectorXd w = A * f + b;
  EXPECT_NEAR(w(0), 0.0, 1e-15);
  EXPECT_NEAR(w(1), 0.0, 1e-15);
  EXPECT_NEAR(w(2), 1.5, 1e-15);
  EXPECT_EQ(active, (std::vector<char>{1, 1, 0}));
}

TEST(LcpPivoting, DependentRowsOfAFaceEndComplementary) {
  // The four corners of a standing domino's base on the floor at an impact (dumped from the
  // dominoes, every digit): a rank-3 Delassus matrix, symmetric under swapping corners 0↔2 and
  // 1↔3. Dantzig's least-squares steps on its dependent rows ended with a push at a corner that
  // separates (w = 3e-3 where f > 0); that answer is now refused, and the ridged retry (as every
  // impact asks) reaches the solution, complementary to round-off and symmetric.
  Eigen::MatrixXd A(4, 4);
  A << 297.631172273689, 272.16939752688086, 83.955958598475306, 58.494183851667174,  //
      272.16939752688086, 297.631172273689, 58.494183851667174, 83.95595859847532,    //
      83.955958598475306, 58.494183851667174, 297.631172273689, 272.16939752688086,   //
      58.494183851667174, 83.95595859847532, 272.16939752688086, 297.631172273689;
  Eigen::VectorXd b(4);
  b << -0.0041345328659468487, -0.025520715018440818, -0.0041345328659468487,
      -0.025520715018440818;
  Eigen::VectorXd f;
  std::vector<char> active;
  solve_lcp_pivoting(A, b, f, active, /*ridge_on_stall=*/true);
  const Eigen::VectorXd w = A * f + b;
  // The ridge moves w by 1e-10 |A| f; 1e-9 |b| bounds that and the solves' round-off.
  const double tol = 1e-9 * b.cwiseAbs().maxCoeff();
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_GE(f(i), 0.0);
    EXPECT_GE(w(i), -tol);
    EXPECT_LE(std::abs(f(i) * w(i)), tol * f.cwiseAbs().maxCoeff());
  }
  EXPECT_NEAR(f(0), f(2), 1e-9 * f.cwiseAbs().maxCoeff());
  EXPECT_NEAR(f(1), f(3), 1e-9 * f.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

// A column of `count` unit masses on the floor, each contact seen by two coincident rows (a
// face's dependent corners): the Delassus matrix J M⁻¹ Jᵀ of 2 count rows, rank count.
Eigen::MatrixXd column_of_masses(int count) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * count, count);
  for (int k = 0; k < count; ++k)
    for (int r = 0; r < 2; ++r) {
      J(2 * k + r, k) = 1.0;
      if (k > 0) J(2 * k + r, k - 1) = -1.0;
    }
  return J * J.transpose();
}

TEST(LcpIterative, MprgpReachesThePivotingAnswerOnARandomDefiniteProblem) {
  // minimise_bounded_qp (mprgp.hpp) on a definite problem with a unique answer, some rows
  // pressing and some separating: it must reach the tolerance asked (1e-10 of |b|) and the
  // pivoting's answer to ~1e-8.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int n = 40;
  Eigen::MatrixXd J(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) J(i, j) = normal(rng);
  const Eigen::MatrixXd A = J * J.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b(i) = normal(rng);
  Eigen::VectorXd exact;
  std::vector<char> active;
  ASSERT_TRUE(solve_lcp_pivoting(A, b, exact, active));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd unit = Eigen::VectorXd::Ones(n);
  const double step = 1.0 / A.cwiseAbs().rowwise().sum().maxCoeff();
  const double tol = 1e-10 * b.cwiseAbs().maxCoeff();
  const double reached = minimise_bounded_qp(
      [&A](const Eigen::VectorXd& y, Eigen::VectorXd& out) { out = A * y; }, b, unit, step, x,
      tol, 10000);
  EXPECT_LE(reached, tol);
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-8 * exact.cwiseAbs().maxCoeff());
  int pressing = 0;
  for (int i = 0; i < n; ++i) pressing += exact(i) > 0.0;
  EXPECT_GT(pressing, 0);
  EXPECT_LT(pressing, n);  // both kinds of row
}

TEST(LcpIterative, ALargeImpactIsSolvedIterativelyAndNeverGainsEnergy) {
  // Above kLargeLcpRows rows a symmetric problem is solved by MPRGP: a column of 150 masses
  // (300 dependent rows), b the contacts' normal speeds (an inelastic impact). The bottom 100
  // fall onto the floor and each other; the top 50 fly up (the 101st leaves at 200 m/s, the
  // rest spread at 0.5 m/s). The answer must be complementary to the pivoting's tolerance, its
  // energy change b·f + ½ fᵀA f (the kinetic energy's) <= 0, the falling ones stopped, the
  // flying ones untouched, and the coincident rows must share their impulse evenly (the
  // ridge's least norm).
  const int count = 150;
  const Eigen::MatrixXd A = column_of_masses(count);
  ASSERT_GT(A.rows(), kLargeLcpRows);
  Eigen::VectorXd b(2 * count);
  for (int k = 0; k < count; ++k)
    b(2 * k) = b(2 * k + 1) = k < 100 ? -1.0 - 0.01 * k : (k == 100 ? 200.0 : 0.5);
  Eigen::VectorXd f;
  std::vector<char> active;
  EXPECT_TRUE(solve_lcp_dissipative(A, b, f, active));
  const Eigen::VectorXd w = A * f + b;
  const double tol = 1e-9 * b.cwiseAbs().maxCoeff();
  for (int i = 0; i < b.size(); ++i) {
    EXPECT_GE(f(i), 0.0);
    EXPECT_GE(w(i), -1e3 * tol) << i;
    if (f(i) > 0.0) {
      EXPECT_LT(std::abs(w(i)), 1e3 * tol) << i;
    }
  }
  EXPECT_LE(b.dot(f) + 0.5 * f.dot(A * f), 0.0);
  for (int k = 0; k < count; ++k) EXPECT_NEAR(f(2 * k), f(2 * k + 1), 1e-6 * f.maxCoeff());
  for (int k = 0; k < 100; ++k) EXPECT_GT(f(2 * k), 0.0) << k;
  for (int k = 100; k < count; ++k) EXPECT_EQ(f(2 * k), 0.0) << k;
}

// The pivoted LDLᵀ's pseudo-inverse is the complete orthogonal decomposition's, on random
// semidefinite matrices of every rank, right-hand sides in the range or not (least squares).
TEST(LeastNorm, ASemidefiniteSolveIsTheCompleteOrthogonalDecompositions) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + (trial * 7) % 61;
    const int rank = 1 + (trial * 13) % n;
    const Eigen::MatrixXd J = Eigen::MatrixXd::NullaryExpr(rank, n, [&] { return normal(rng); });
    const Eigen::MatrixXd M = J.transpose() * J;
    Eigen::VectorXd rhs = Eigen::VectorXd::NullaryExpr(n, [&] { return normal(rng); });
    if (trial % 2 == 0) rhs = M * rhs;
    Eigen::VectorXd x;
    ASSERT_TRUE(least_norm_psd(M, rhs, n * Eigen::NumTraits<double>::epsilon(), x));
    const Eigen::VectorXd y = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(M).solve(rhs);
    EXPECT_LT((x - y).norm(), 1e-9 * y.norm()) << "n " << n << " rank " << rank;
  }
}

// Two equal rows and an independent one: a pivot by the diagonal before its update (Eigen's
// LDLT) takes the second equal row next, whose pivot is zero, before the independent one. The
// pseudo-inverse splits the equal rows evenly; an indefinite matrix is refused.
TEST(LeastNorm, EqualRowsAreSplitEvenlyAndAnIndefiniteMatrixIsRefused) {
  Eigen::MatrixXd M(3, 3);
  M << 1.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.5;
  Eigen::VectorXd rhs(3), x;
  rhs << 2.0, 2.0, 1.0;
  ASSERT_TRUE(least_norm_psd(M, rhs, 1e-15, x));
  EXPECT_NEAR(x(0), 1.0, 1e-14);
  EXPECT_NEAR(x(1), 1.0, 1e-14);
  EXPECT_NEAR(x(2), 2.0, 1e-14);
  M(2, 2) = -0.5;
  EXPECT_FALSE(least_norm_psd(M, rhs, 1e-15, x));
}

}  // namespace
}  // namespace tumble
