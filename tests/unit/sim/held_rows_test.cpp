#include "../../../src/sim/held_rows.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>

namespace tumble {
namespace {

// A tower of `count` unit cubes (1 kg, I = m/6) standing on the floor, each resting on the one
// below by its four corners: 4 count contacts, every one sticking (two tangent rows each), so
// 12 count rows (the sparse solve is called directly, whatever the size).
struct Tower {
  Frames f;
  std::vector<MassInfo> m;
  std::vector<Vec3> dir;
  HeldRows rows;

  explicit Tower(int count, double g = 9.81) {
    const double corners[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
    for (int k = 0; k < count; ++k) m.push_back({1.0, Mat3::Identity() * 6.0});
    Eigen::VectorXd b(4 * count);
    for (int k = 0; k < count; ++k)
      for (const auto& c : corners) {
        ContactFrame fr{};
        fr.pa = fr.pb = Vec3::Zero();
        fr.n = Vec3::UnitY();
        fr.ra = Vec3(c[0], 0.5, c[1]);  // from the centre of the box below (unused: the floor)
        fr.rb = Vec3(c[0], -0.5, c[1]);
        SideGeometry a, bside;
        if (k > 0) a = {k - 1, fr.ra, fr.ra};
        bside = {k, fr.rb, fr.rb};
        f.frame.push_back(fr);
        f.a.push_back(a);
        f.b.push_back(bside);
        f.round_pair.push_back(false);
        dir.push_back(fr.n);
        // Without contact forces every box falls alike: only the floor's rows approach.
        b(static_cast<Eigen::Index>(f.frame.size() - 1)) = k == 0 ? -g : 0.0;
      }
    rows.f = &f;
    rows.m = &m;
    rows.dir = &dir;
    rows.b = b;
    for (int i = 0; i < 4 * count; ++i) {
      rows.sticking.push_back(i);
      rows.t.push_back(Vec3::UnitX());
      rows.t.push_back(Vec3::UnitZ());
    }
    rows.bt = Eigen::VectorXd::Zero(8 * count);
  }
};

// Statics of a tower of `count` boxes: the interface under box k carries the weight of the boxes
// from k up, a quarter at each corner; to 1e-7 of the largest force (see the first test).
void expect_tower_statics(const Eigen::VectorXd& normal, int count) {
  const double top = count * 9.81 / 4.0;
  for (int k = 0; k < count; ++k)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(normal(4 * k + c), (count - k) * 9.81 / 4.0, 1e-7 * top) << k << " " << c;
}

TEST(HeldRows, ATowerOfBoxesIsHeldByEqualCornerForcesWithoutFriction) {
  // Statics: the interface under box k carries the weight of the boxes from k up, a quarter at
  // each corner (the symmetric split of four dependent rows), and nothing pulls sideways. The
  // ridge (1e-8 of the largest diagonal) and three refinements leave the range exact to round-off;
  // the split among dependent rows keeps the right-hand side's round-off divided by the ridge,
  // ~1e-16 / 1e-8: 1e-7 of the largest force.
  const int count = 8;
  Tower t(count);
  std::vector<char> active;
  Eigen::VectorXd normal, tangential;
  ASSERT_TRUE(solve_held_rows_sparse(t.rows, active, normal, tangential));
  expect_tower_statics(normal, count);
  EXPECT_LT(tangential.cwiseAbs().maxCoeff(), 1e-7 * count * 9.81 / 4.0);
  for (char a : active) EXPECT_TRUE(a);
}

TEST(HeldRows, PivotsBegunFarFromTheAnswerSettleFromTheQuadraticProgramsPressingRows) {
  // A frictionless tower of 40 boxes begun from only the top box's corners clamped: each round of
  // block pivots clamps one more interface from the floor up (4 rows a round, so they stall into
  // single pivots), far more rounds than the pivots are given. They start again from the rows
  // that press at the quadratic program's minimiser (MPRGP), which on this tower are all of
  // them, and settle at once: the answer is exact, not the iterative one.
  const int count = 40;
  Tower t(count);
  t.rows.sticking.clear();
  t.rows.t.clear();
  t.rows.bt.resize(0);
  std::vector<char> active(4 * count, 0);
  for (int c = 0; c < 4; ++c) active[static_cast<std::size_t>(4 * (count - 1) + c)] = 1;
  Eigen::VectorXd normal, tangential;
  double residual = -1.0;
  ASSERT_TRUE(solve_held_rows_sparse(t.rows, active, normal, tangential, nullptr, &residual));
  expect_tower_statics(normal, count);
  for (char a : active) EXPECT_TRUE(a);
  EXPECT_EQ(residual, 0.0);
}

TEST(HeldRows, ARowsLessSomeFromTheCachedFactorisationEqualsAFreshSolve) {
  // hold_or_slip frees sticking contacts one at a time at one state: the same rows less two
  // tangent rows. The bordered solve from the cached factorisation must give the fresh answer.
  Tower t(8);
  HeldRowsCache cache;
  std::vector<char> active;
  Eigen::VectorXd normal, tangential;
  // A sideways push on the top box (its four corners' slip along x), so that the tangent rows
  // carry force.
  for (int c = 0; c < 4; ++c) t.rows.bt(2 * (4 * 7 + c)) = 0.3;
  ASSERT_TRUE(solve_held_rows_sparse(t.rows, active, normal, tangential, &cache));
  HeldRows fewer = t.rows;
  fewer.sticking.erase(fewer.sticking.begin() + 5);
  fewer.t.erase(fewer.t.begin() + 10, fewer.t.begin() + 12);
  Eigen::VectorXd bt(fewer.bt.size() - 2);
  bt << t.rows.bt.head(10), t.rows.bt.tail(t.rows.bt.size() - 12);
  fewer.bt = bt;
  std::vector<char> active_cached = active, active_fresh = active;
  Eigen::VectorXd n_cached, t_cached, n_fresh, t_fresh;
  ASSERT_TRUE(solve_held_rows_sparse(fewer, active_cached, n_cached, t_cached, &cache));
  ASSERT_TRUE(solve_held_rows_sparse(fewer, active_fresh, n_fresh, t_fresh));
  const double scale = n_fresh.cwiseAbs().maxCoeff();
  EXPECT_LT((n_cached - n_fresh).cwiseAbs().maxCoeff(), 1e-7 * scale);
  EXPECT_LT((t_cached - t_fresh).cwiseAbs().maxCoeff(), 1e-7 * scale);
  EXPECT_GT(t_fresh.cwiseAbs().maxCoeff(), 1e-3);  // the push is carried by friction
}

TEST(HeldRows, ABoxThatLiftsOffIsFreedAndTheRestSolved) {
  // The top box pulled up harder than gravity (15 m/s² away from the free fall of the box under
  // it, which the tower's support turns into 15 − 9.81 away from a box at rest): its four corners
  // must separate (no pull), the tower below still held. Begun from all clamped, the block pivots
  // free them.
  Tower t(8);
  for (int c = 0; c < 4; ++c) t.rows.b(4 * 7 + c) = 15.0;
  std::vector<char> active;
  Eigen::VectorXd normal, tangential;
  ASSERT_TRUE(solve_held_rows_sparse(t.rows, active, normal, tangential));
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(normal(4 * 7 + c), 0.0);
    EXPECT_FALSE(active[static_cast<std::size_t>(4 * 7 + c)]);
  }
  const double top = 8 * 9.81 / 4.0;
  for (int k = 0; k < 7; ++k)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(normal(4 * k + c), (7 - k) * 9.81 / 4.0, 1e-7 * top);
}

TEST(HeldRows, TheCacheRemembersTheLastFourUnsettledFrictionProblems) {
  // A problem is its sticking contacts and which contacts slide; both must match. The oldest of
  // five is forgotten, and remembering one again does not push another out.
  HeldRowsCache cache;
  const std::vector<char> none(6, 0), first(6, 0), second = {1, 0, 0, 0, 0, 0};
  for (int k = 0; k < 4; ++k) cache.remember_unsettled({k}, none);
  cache.remember_unsettled({0}, none);
  EXPECT_TRUE(cache.unsettled({0}, none));
  EXPECT_FALSE(cache.unsettled({0}, second));
  EXPECT_FALSE(cache.unsettled({0, 1}, none));
  cache.remember_unsettled({4}, second);
  EXPECT_FALSE(cache.unsettled({0}, none));
  for (int k = 1; k < 4; ++k) EXPECT_TRUE(cache.unsettled({k}, first));
  EXPECT_TRUE(cache.unsettled({4}, second));
}

TEST(HeldRows, LeastNormSolveMatchesTheDecompositionOnALargeDependentSystem) {
  // Above kSparseRows rows least_norm_solve takes the ridged sparse factorisation: on a
  // consistent system with dependent rows it must give the least-norm answer to ~1e-9.
  const int n = 2 * kSparseRows;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n / 2);
  for (int i = 0; i < n; ++i) {
    J(i, (i / 2) % (n / 2)) = 1.0;
    J(i, (i / 2 + 1) % (n / 2)) = 0.5;
  }
  const Eigen::MatrixXd M = J * J.transpose();  // rank n/2: every row twice
  Eigen::VectorXd x0 = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  const Eigen::VectorXd rhs = M * x0;
  const Eigen::VectorXd x = least_norm_solve(M, rhs);
  const Eigen::VectorXd exact = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(M).solve(rhs);
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-7 * exact.cwiseAbs().maxCoeff());
  EXPECT_LT((M * x - rhs).norm(), 1e-8 * rhs.norm());
}

// A block-diagonal system with its blocks' rows interleaved, as contacts of groups that share
// no body come in an island's order: block 0 regular, block 1 singular and consistent (every
// row twice, a face's dependent corners), block 2 singular and inconsistent (least squares),
// and no row of block 3 (a subset of the rows may leave a group out).
struct Blocks {
  Eigen::MatrixXd M;
  Eigen::VectorXd rhs;
  std::vector<int> group;

  Blocks() {
    const std::vector<int> of = {1, 0, 2, 1, 0, 2, 1, 4, 0, 2, 1, 4};
    const int n = static_cast<int>(of.size());
    group = of;
    // Block b's rows span `columns[b]` columns of their own: 3 rows in 3 (block 0), 4 in 2
    // (block 1), 3 in 2 (block 2), 2 in 2 (block 4).
    const int columns[5] = {3, 2, 2, 0, 2};
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, 3 * 5);
    int seen[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
      const int b = of[static_cast<std::size_t>(i)], k = seen[b]++;
      J(i, 3 * b + k % columns[b]) = 1.0 + 0.1 * k;
      J(i, 3 * b + (k + 1) % columns[b]) += 0.5;
    }
    M = J * J.transpose();
    rhs = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    Eigen::VectorXd x0 = Eigen::VectorXd::LinSpaced(n, 0.5, -0.7);
    const Eigen::VectorXd consistent = M * x0;
    for (int i = 0; i < n; ++i)
      if (of[static_cast<std::size_t>(i)] == 1) rhs(i) = consistent(i);
  }
};

TEST(HeldRows, BlockLeastNormEqualsTheWholeSolveOnABlockDiagonalSystem) {
  // The least-norm least-squares answer of a block-diagonal system is its blocks' answers side
  // by side: compared with a complete orthogonal decomposition of the whole, to round-off of
  // the pivoted LDLᵀ on these small blocks (1e-9 of the answer).
  const Blocks s;
  const Eigen::VectorXd x = block_least_norm(s.M, s.rhs, s.group);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-12);
  cod.compute(s.M);
  const Eigen::VectorXd exact = cod.solve(s.rhs);
  ASSERT_EQ(x.size(), exact.size());
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-9 * exact.cwiseAbs().maxCoeff());
  // The inconsistent block is solved in least squares: a residual there is, orthogonal to M's
  // range.
  EXPECT_GT((s.M * x - s.rhs).norm(), 1e-3 * s.rhs.norm());
  EXPECT_LT((s.M * (s.M * x - s.rhs)).cwiseAbs().maxCoeff(), 1e-9 * s.rhs.norm());
}

TEST(HeldRows, BlockLeastNormReadsNoEntryBetweenBlocksAndOneBlockIsTheWholeSolve) {
  const Blocks s;
  Eigen::MatrixXd coupled = s.M;
  for (Eigen::Index i = 0; i < coupled.rows(); ++i)
    for (Eigen::Index j = 0; j < coupled.cols(); ++j)
      if (s.group[static_cast<std::size_t>(i)] != s.group[static_cast<std::size_t>(j)])
        coupled(i, j) = 1e3 + static_cast<double>(i + j);
  EXPECT_EQ(block_least_norm(coupled, s.rhs, s.group), block_least_norm(s.M, s.rhs, s.group));
  // Every row in one block: least_norm_solve itself, to the bit.
  const std::vector<int> one(s.group.size(), 0);
  EXPECT_EQ(block_least_norm(s.M, s.rhs, one), least_norm_solve(s.M, s.rhs));
}

}  // namespace
}  // namespace tumble
