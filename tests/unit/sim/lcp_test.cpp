#include "../../../src/sim/lcp.hpp"

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
