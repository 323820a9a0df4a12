#include "lcp.hpp"
#include "mprgp.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

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

namespace {

bool symmetric(const Eigen::MatrixXd& A) {
  return (A - A.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * A.cwiseAbs().maxCoeff();
}

// Minimum-norm solution of A[C, C] x = rhs[C] for the rows in `set`.
Eigen::VectorXd solve_subset(const Eigen::MatrixXd& A, const std::vector<int>& set,
                             const Eigen::VectorXd& rhs) {
  const int k = static_cast<int>(set.size());
  Eigen::MatrixXd As(k, k);
  Eigen::VectorXd bs(k);
  for (int r = 0; r < k; ++r) {
    bs(r) = rhs(set[r]);
    for (int c = 0; c < k; ++c) As(r, c) = A(set[r], set[c]);
  }
  return least_norm(As, bs, static_cast<double>(k) * Eigen::NumTraits<double>::epsilon());
}

void projected_gauss_seidel(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                            Eigen::VectorXd& f) {
  const int n = static_cast<int>(b.size());
  for (int iter = 0; iter < 500; ++iter)
    for (int i = 0; i < n; ++i)
      if (A(i, i) > 0.0) f(i) = std::max(0.0, f(i) - (A.row(i).dot(f) + b(i)) / A(i, i));
}

}  // namespace

namespace {

// Dantzig pivoting; false when its pivot budget runs out or no step is bounded.
bool pivot(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
           std::vector<char>& active) {
  const int n = static_cast<int>(b.size());
  f = Eigen::VectorXd::Zero(n);
  active.resize(static_cast<std::size_t>(n), 0);
  if (n == 0) return true;
  const double scale_w = 1e-9 * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  const double scale_f = scale_w / std::max(A.cwiseAbs().maxCoeff(), 1e-300);
  // Warm start: the last clamped set, solved at once; kept if it is complementary (the usual
  // case for contacts that did not change mode since the last evaluation). Otherwise a few
  // block pivots (Kostreva's; Júdice and Pires): every clamped row whose force came out
  // negative is freed and every free row that is violated is clamped, all at once. Rows that a
  // symmetric pose makes equal (the two ends of an edge) then change together, where Dantzig's
  // one pivot at a time frees one of them by round-off and keeps the other: with sliding
  // friction the LCP has both answers, and the lopsided one turns a planar scene out of its
  // plane. Block pivoting can cycle when A is not a P-matrix: after a few it hands over.
  std::vector<char> set_now(active.begin(), active.end());
  for (int round = 0; round < 4; ++round) {
    std::vector<int> C;
    for (int i = 0; i < n; ++i)
      if (set_now[i]) C.push_back(i);
    if (C.empty() && round == 0) break;
    f.setZero();
    bool ok = true;
    std::vector<char> next = set_now;
    if (!C.empty()) {
      const Eigen::VectorXd fc = solve_subset(A, C, -b);
      for (std::size_t r = 0; r < C.size(); ++r) {
        if (fc(r) < -scale_f) next[C[r]] = 0, ok = false;
        f(C[r]) = std::max(fc(r), 0.0);
      }
    }
    const Eigen::VectorXd w = A * f + b;
    for (int i = 0; i < n; ++i) {
      if (set_now[i] && !(std::abs(w(i)) <= 1e3 * scale_w) && next[i]) ok = false;
      if (!set_now[i] && w(i) < -scale_w) next[i] = 1, ok = false;
    }
    if (ok) {
      for (int i = 0; i < n; ++i) active[i] = set_now[i];
      return true;
    }
    if (next == set_now) break;
    set_now.swap(next);
  }
  f.setZero();
  // Dantzig / Baraff: f = 0, a = b; drive every row with a < 0 to a = 0 or f = 0.
  std::vector<int> C;
  std::vector<char> clamped(static_cast<std::size_t>(n), 0);
  Eigen::VectorXd a = b;
  int pivots = 0;
  const int budget = 10 * n + 50;
  // A step of length zero changes only which rows are clamped. Where such steps come back to a
  // clamped set they have been at, with f and a the same to the bit, the pivots from there
  // repeat exactly, for ever: the method cannot finish (a pyramid of 6 rows struck by a ball,
  // to 0.211 s: every solve that ran to the budget, 1 380 pivots of a 133-row problem, had
  // entered a cycle of three zero steps after 14–60). The states since the last step that
  // moved are kept to see that.
  struct Still {
    std::vector<char> clamped;
    Eigen::VectorXd f, a;
  };
  std::vector<Still> since_moved;
  for (int d = 0; d < n; ++d) {
    if (a(d) >= -scale_w) continue;
    since_moved.clear();
    // Drive row d.
    while (a(d) < -scale_w) {
      if (++pivots > budget) return false;
      // Direction: Δf_d = 1, the clamped rows keep Δa = 0: A_CC Δf_C = −A_Cd.
      std::vector<int> set;
      for (int i = 0; i < n; ++i)
        if (clamped[i]) set.push_back(i);
      Eigen::VectorXd df = Eigen::VectorXd::Zero(n);
      df(d) = 1.0;
      if (!set.empty()) {
        const Eigen::VectorXd x = solve_subset(A, set, -A.col(d));
        for (std::size_t r = 0; r < set.size(); ++r) df(set[r]) = x(r);
      }
      const Eigen::VectorXd da = A * df;
      // The largest step that keeps f >= 0 on clamped rows and a >= 0 on the free ones.
      double s = INFINITY;
      int j = -1;
      if (da(d) > 0.0) s = -a(d) / da(d), j = d;
      for (int i = 0; i < n; ++i) {
        if (i == d) continue;
        if (clamped[i] && df(i) < 0.0) {
          const double si = -f(i) / df(i);
          if (si < s) s = si, j = i;
        } else if (!clamped[i] && f(i) == 0.0 && da(i) < 0.0 && a(i) >= -scale_w) {
          const double si = std::max(0.0, -a(i)) / -da(i);
          if (si < s) s = si, j = i;
        }
      }
      if (j < 0 || !std::isfinite(s)) return false;  // unbounded: none reachable (friction)
      f += s * df;
      a += s * da;
      if (j == d) {
        clamped[d] = 1;
        a(d) = 0.0;
        break;
      }
      if (clamped[j]) {
        clamped[j] = 0;
        f(j) = 0.0;
      } else {
        clamped[j] = 1;
        a(j) = 0.0;
      }
      if (s > 0.0) {
        since_moved.clear();
        continue;
      }
      for (const Still& was : since_moved)
        if (was.clamped == clamped && was.f == f && was.a == a) return false;  // a cycle
      since_moved.push_back({clamped, f, a});
    }
  }
  for (int i = 0; i < n; ++i) {
    f(i) = std::max(f(i), 0.0);
    active[i] = clamped[i];
  }
  return true;
}

// Whether f solves the LCP within the pivoting's tolerances: f >= 0, w = A f + b >= 0 (the
// signs, where `signs`), and w = 0 where f > 0, to `slack` times 1e-9 |b|.
bool complementary(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& f,
                   double slack = 1e3, bool signs = true) {
  const double scale_w = 1e-9 * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  const double scale_f = scale_w / std::max(A.cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::VectorXd w = A * f + b;
  for (Eigen::Index i = 0; i < b.size(); ++i) {
    if (signs && (f(i) < -scale_f || w(i) < -scale_w)) return false;
    if (f(i) > scale_f && std::abs(w(i)) > slack * scale_w) return false;
  }
  return true;
}

// On dependent rows (a face's four corners among other contacts) Dantzig's least-squares steps
// can end far off complementarity: a force where its row separates at a few percent of |b|.
// That answer is no solution. Round-off of a regular solve is some 1e-12 of |b|, so 1e-3 of it
// only catches the gross failures.
bool grossly_off(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& f) {
  return !complementary(A, b, f, /*slack=*/1e6, /*signs=*/false);
}

// Where a row is free at w = 0 (degenerate: a contact that carries nothing and does not move
// away), the LCP has other solutions on the same rows, as many as A's dependent rows allow: a
// domino's edge on the floor is held by both its ends or by one alone. Frictionless, they all
// move the bodies alike (A's null space is J's), but friction and the contact forces' split do
// not: a lopsided split on a symmetric pose (Dantzig's pivots freeing one end by round-off)
// turns a planar row of dominoes out of its plane. The answer kept is the minimum-norm one over
// every row at w = 0 (free and clamped), which a symmetric pose makes symmetric; it is kept
// only where it is a solution (no force negative; for an unsymmetric A, the free rows still
// not violated).
void canonical_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
                     std::vector<char>& active) {
  const int n = static_cast<int>(b.size());
  const double scale_w = 1e-9 * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  const double scale_f = scale_w / std::max(A.cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::VectorXd w = A * f + b;
  std::vector<int> S;
  bool degenerate = false;
  for (int i = 0; i < n; ++i) {
    const bool carries = f(i) > scale_f;
    if (carries || std::abs(w(i)) <= scale_w) S.push_back(i);
    degenerate |= !carries && std::abs(w(i)) <= scale_w && A(i, i) > 0.0;
  }
  if (!degenerate) return;
  const int k = static_cast<int>(S.size());
  Eigen::MatrixXd As(k, k);
  Eigen::VectorXd bs(k);
  for (int r = 0; r < k; ++r) {
    bs(r) = -b(S[r]);
    for (int c = 0; c < k; ++c) As(r, c) = A(S[r], S[c]);
  }
  const Eigen::VectorXd g = least_norm(As, bs, 1e-10);
  Eigen::VectorXd split = Eigen::VectorXd::Zero(n);
  for (int r = 0; r < k; ++r) {
    if (g(r) < -scale_f) return;
    split(S[r]) = std::max(g(r), 0.0);
  }
  if (!complementary(A, b, split)) return;
  f = split;
  active.assign(static_cast<std::size_t>(n), 0);
  for (int r = 0; r < k; ++r) active[static_cast<std::size_t>(S[r])] = f(S[r]) > 0.0;
}

// Lemke's complementary pivoting (Cottle, Pang & Stone, "The Linear Complementarity Problem",
// 4.4), for what Dantzig's method cannot finish: sliding friction makes A unsymmetric, and
// then principal pivoting may cycle or find its step unbounded although a solution exists.
// Lemke's method finds one for every copositive-plus A (contact matrices, and those of
// moderate friction) or ends on a ray, proving there is none it can reach. The system
// w − A f − d z0 = b, d = 1, on a dense tableau (a rank-one update per pivot, O(n²)); the
// lexicographic ratio test (rows of the basis inverse) makes it finite on degenerate problems,
// which contact gives (four corners of a face). The clamped set found is solved again by the
// minimum-norm solve of the principal pivoting, so the answer is the same kind as its.
// In floating point the lexicographic test can still be defeated by round-off: the path comes
// back to a basis it has been at, with the same variable leaving, and goes round again. Round-off
// can also take it out of such a loop, so a path ends only after n / 2 such returns. (A pyramid
// of 6 rows struck by a ball, to 0.25 s: 264 Lemke solves came back to a basis; 260 of them ran
// on to the pivot cap, 20 n + 50, round loops of 39 to 245 states, 60 % of the run's wall
// time; 4, of 126–144 rows, found a solution after 5, 12, 46 and 337 returns. From 0.25 to
// 0.38 s, 6 of 3 279 solves that found one had come back, after 18, 23, 34, 42, 79 and 266
// returns on 95–132 rows, and 1 218 went round to 3 n returns, three quarters of the pivots:
// n / 2 keeps four of those six.)
bool lemke(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
           std::vector<char>& active) {
  const int n = static_cast<int>(b.size());
  const int z0 = 2 * n;  // columns: w (0..n-1), f (n..2n-1), the artificial z0
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, 2 * n + 1);
  T.leftCols(n).setIdentity();
  T.middleCols(n, n) = -A;
  T.col(z0).setConstant(-1.0);
  Eigen::VectorXd rhs = b;
  std::vector<int> basis(static_cast<std::size_t>(n));
  std::iota(basis.begin(), basis.end(), 0);
  // Row r divided by the pivot, then that row's multiple taken from every other row: one
  // rank-one update, column by column (T is stored by columns; row by row it was strided).
  Eigen::VectorXd x(n);
  Eigen::RowVectorXd pivot_row(T.cols());
  auto exchange = [&](int r, int c) {
    const double p = T(r, c);
    T.row(r) /= p;
    rhs(r) /= p;
    x = T.col(c);
    x(r) = 0.0;
    pivot_row = T.row(r);
    T.noalias() -= x * pivot_row;
    rhs -= rhs(r) * x;
    basis[static_cast<std::size_t>(r)] = c;
  };
  Eigen::Index first = 0;
  b.minCoeff(&first);
  int leaving = basis[static_cast<std::size_t>(first)];
  exchange(static_cast<int>(first), z0);
  // Every state the path has been in: its basis (sorted) and the variable that left last,
  // which fixes the next pivot.
  std::set<std::pair<std::vector<int>, int>> been;
  int returns = 0;
  for (int pivots = 0; pivots < 20 * n + 50; ++pivots) {
    std::vector<int> state = basis;
    std::sort(state.begin(), state.end());
    if (!been.emplace(std::move(state), leaving).second && ++returns > n / 2) return false;
    const int entering = leaving < n ? leaving + n : leaving - n;  // the complement
    const double column = T.col(entering).cwiseAbs().maxCoeff();
    int r = -1;
    for (int i = 0; i < n; ++i) {
      const double a = T(i, entering);
      if (!(a > 1e-12 * column)) continue;
      if (r < 0) {
        r = i;
        continue;
      }
      // The smallest ratio; ties broken by z0 leaving, then lexicographically.
      const double ratio = rhs(i) / a, best = rhs(r) / T(r, entering);
      const double tie = 1e-14 * std::max(std::abs(best), 1e-300);
      if (ratio < best - tie) {
        r = i;
      } else if (ratio <= best + tie && basis[static_cast<std::size_t>(r)] != z0) {
        if (basis[static_cast<std::size_t>(i)] == z0) {
          r = i;
          continue;
        }
        for (int k = 0; k < n; ++k) {
          const double li = T(i, k) / a, lr = T(r, k) / T(r, entering);
          if (li < lr - 1e-14) {
            r = i;
            break;
          }
          if (li > lr + 1e-14) break;
        }
      }
    }
    if (r < 0) return false;  // a ray: no solution on this path
    leaving = basis[static_cast<std::size_t>(r)];
    exchange(r, entering);
    if (leaving != z0) continue;
    // Complementary: the forces in the basis are the clamped set.
    std::vector<int> clamped;
    for (int i = 0; i < n; ++i)
      if (basis[static_cast<std::size_t>(i)] >= n && basis[static_cast<std::size_t>(i)] < z0)
        clamped.push_back(basis[static_cast<std::size_t>(i)] - n);
    std::sort(clamped.begin(), clamped.end());
    f = Eigen::VectorXd::Zero(n);
    const Eigen::VectorXd fc = solve_subset(A, clamped, -b);
    for (std::size_t k = 0; k < clamped.size(); ++k) f(clamped[k]) = std::max(fc(k), 0.0);
    if (!complementary(A, b, f)) {  // the tableau's own values, where the re-solve is worse
      f.setZero();
      for (int i = 0; i < n; ++i)
        if (basis[static_cast<std::size_t>(i)] >= n && basis[static_cast<std::size_t>(i)] < z0)
          f(basis[static_cast<std::size_t>(i)] - n) = std::max(rhs(i), 0.0);
      if (!complementary(A, b, f)) return false;
    }
    active.assign(static_cast<std::size_t>(n), 0);
    for (int i : clamped) active[static_cast<std::size_t>(i)] = 1;
    return true;
  }
  return false;
}

}  // namespace

namespace {

// Above kLargeLcpRows rows with a symmetric A (a struck pile's impact, or its held forces
// without friction): MPRGP on the quadratic program of A with a diagonal of 1e-10 of its
// largest added (mprgp.hpp), Jacobi-scaled, from f = 0, to 1e-9 |b| (the pivoting's tolerance)
// within kLargeLcpIterations. Dantzig's pivots solve a dense subsystem each (a 557-row impact:
// minutes), Lemke's method pivots a dense tableau. True where the tolerance was reached; the
// answer is kept either way (q only decreases from f = 0: an impact's energy change b·f + ½fᵀAf
// is q, never above zero).
constexpr int kLargeLcpIterations = 4000;

bool solve_large(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
                 std::vector<char>& active) {
  const Eigen::Index n = b.size();
  const double ridge = 1e-10 * std::max(A.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd scale(n), unit(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = A(i, i) + ridge;
    scale(i) = A(i, i) > 0.0 ? 1.0 / std::sqrt(d) : 0.0;
    unit(i) = A(i, i) > 0.0 ? std::sqrt(d) : 0.0;
  }
  Eigen::MatrixXd M = scale.asDiagonal() * A * scale.asDiagonal();
  M.diagonal() += ridge * scale.cwiseAbs2();
  const double step = 1.0 / std::max(M.cwiseAbs().rowwise().sum().maxCoeff(), 1e-300);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const double tol = 1e-9 * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  const double reached = minimise_bounded_qp(
      [&M](const Eigen::VectorXd& y, Eigen::VectorXd& out) { out.noalias() = M * y; },
      scale.cwiseProduct(b), unit, step, x, tol, kLargeLcpIterations);
  f = scale.cwiseProduct(x);
  active.assign(static_cast<std::size_t>(n), 0);
  for (Eigen::Index i = 0; i < n; ++i) active[static_cast<std::size_t>(i)] = f(i) > 0.0;
  return reached <= tol;
}

}  // namespace

bool least_norm_psd(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs, double threshold,
                    Eigen::VectorXd& x) {
  const Eigen::Index n = M.rows();
  if (n == 0) return x = Eigen::VectorXd::Zero(0), true;
  const double first = M.diagonal().maxCoeff();
  if (!(first > 0.0)) {
    if (M.cwiseAbs().maxCoeff() != 0.0) return false;
    return x = Eigen::VectorXd::Zero(n), true;
  }
  // LDLᵀ, left-looking, the largest diagonal of what is left to factor pivoted first (Eigen's
  // LDLT pivots by the diagonal before its update, so its pivots do not fall in order and a
  // zero one can come before others): a semidefinite M's pivots then fall, and the rank is
  // where they reach the cut. W is M with the pivots' rows and columns exchanged; `left` the
  // diagonal of what is left to factor.
  const double cut = std::max(threshold, 1e-12) * first;
  Eigen::MatrixXd W = M;
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd D = Eigen::VectorXd::Zero(n), left = M.diagonal(), scaled(n);
  std::vector<Eigen::Index> perm(static_cast<std::size_t>(n));
  std::iota(perm.begin(), perm.end(), Eigen::Index{0});
  Eigen::Index r = 0;
  for (; r < n; ++r) {
    Eigen::Index p = 0;
    left.tail(n - r).maxCoeff(&p);
    p += r;
    if (!(left(p) > cut)) break;
    if (p != r) {
      W.row(r).swap(W.row(p));
      W.col(r).swap(W.col(p));
      L.row(r).head(r).swap(L.row(p).head(r));
      std::swap(left(r), left(p));
      std::swap(perm[static_cast<std::size_t>(r)], perm[static_cast<std::size_t>(p)]);
    }
    D(r) = left(r);
    L(r, r) = 1.0;
    const Eigen::Index m = n - r - 1;
    scaled.head(r) = D.head(r).cwiseProduct(L.row(r).head(r).transpose());
    L.col(r).tail(m) = W.col(r).tail(m);
    L.col(r).tail(m).noalias() -= L.bottomLeftCorner(m, r) * scaled.head(r);
    L.col(r).tail(m) /= D(r);
    left.tail(m) -= D(r) * L.col(r).tail(m).cwiseAbs2();
  }
  if (r < n && left.tail(n - r).minCoeff() < -1e-9 * first) return false;
  // M = Pᵀ B D Bᵀ P with B = [L1; L2], L's first r columns (unit lower trapezoidal, full
  // rank), so M⁺ = Pᵀ B (BᵀB)⁻¹ D⁻¹ (BᵀB)⁻¹ Bᵀ P. Where few rows depend on the others, through
  // M's null space instead, spanned by N = [−L1⁻ᵀ L2ᵀ; I] (n − r columns): the right-hand
  // side projected off it (onto M's range), solved on the first r rows, and the solution
  // projected off it. The cheaper of the two (n r² against r² (n − r) + n (n − r)²).
  const Eigen::Index k = n - r;
  const auto L1 = L.topLeftCorner(r, r).triangularView<Eigen::UnitLower>();
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) y(i) = rhs(perm[static_cast<std::size_t>(i)]);
  const double by_null = static_cast<double>(r * r * k + n * k * k);
  const double by_range = static_cast<double>(n * r * r) / 2.0;
  if (k == 0) {
    L1.solveInPlace(y);
    y = y.cwiseQuotient(D);  // r == n
    L1.transpose().solveInPlace(y);
  } else if (by_range < by_null) {
    const auto B = L.leftCols(r);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(r, r);
    G.selfadjointView<Eigen::Lower>().rankUpdate(B.transpose());
    const Eigen::LLT<Eigen::MatrixXd> llt(G.selfadjointView<Eigen::Lower>());
    Eigen::VectorXd z = llt.solve(B.transpose() * y);
    z = llt.solve(Eigen::VectorXd(z.cwiseQuotient(D.head(r))));
    y = B * z;
  } else {
    Eigen::MatrixXd N(n, k);
    N.topRows(r) = -L.bottomLeftCorner(k, r).transpose();
    L1.transpose().solveInPlace(N.topRows(r));
    N.bottomRows(k).setIdentity();
    const Eigen::LLT<Eigen::MatrixXd> NtN(N.transpose() * N);
    auto off_null = [&](Eigen::VectorXd& v) { v -= N * NtN.solve(N.transpose() * v); };
    off_null(y);
    y.tail(k).setZero();
    L1.solveInPlace(y.head(r));
    y.head(r) = y.head(r).cwiseQuotient(D.head(r));
    L1.transpose().solveInPlace(y.head(r));
    off_null(y);
  }
  x.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) x(perm[static_cast<std::size_t>(i)]) = y(i);
  return true;
}

Eigen::VectorXd least_norm(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs, double threshold) {
  Eigen::VectorXd x;
  if (symmetric(M) && least_norm_psd(0.5 * (M + M.transpose()), rhs, threshold, x)) return x;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(threshold);  // before compute(): Eigen reads it there
  cod.compute(M);
  return cod.solve(rhs);
}

bool solve_lcp_pivoting(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
                        std::vector<char>& active, bool ridge_on_stall, bool last_resort) {
  if (b.size() > kLargeLcpRows && symmetric(A)) return solve_large(A, b, f, active);
  bool stalled = !pivot(A, b, f, active);
  if (!stalled && !grossly_off(A, b, f)) return canonical_split(A, b, f, active), true;
  // Contact matrices are only semidefinite: four coplanar points of a face, or a light body
  // pressed between a heavy one and the floor, give dependent rows, where pivoting can stall or
  // end off complementarity (and its least-squares steps choose among many force distributions
  // by round-off, so a symmetric stack would get an asymmetric push). Then a diagonal of 1e-10
  // of the largest one makes the matrix definite: the solution is unique (for a symmetric pose,
  // symmetric) and Dantzig's method reaches it; it moves w = A f + b by 1e-10 |A| f, a tenth of
  // the tolerance. On a stall only where the caller asks (impacts: a push must not depend on
  // round-off), so that every regular solve stays exact to round-off; an answer off
  // complementarity is no answer, and always gets the retry.
  if (ridge_on_stall || !stalled) {
    Eigen::MatrixXd ridged = A;
    ridged.diagonal().array() += 1e-10 * std::max(A.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    std::fill(active.begin(), active.end(), 0);
    if (pivot(ridged, b, f, active) && !grossly_off(A, b, f))
      return canonical_split(A, b, f, active), true;
  }
  if (lemke(A, b, f, active)) return canonical_split(A, b, f, active), true;
  // No method reached a solution (a friction problem without one: Painlevé's paradox).
  f = Eigen::VectorXd::Zero(b.size());
  if (last_resort) projected_gauss_seidel(A, b, f);
  active.assign(static_cast<std::size_t>(b.size()), 0);
  return false;
}

bool solve_lcp_dissipative(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& f,
                           std::vector<char>& active, bool ridge_on_stall) {
  // The energy change of impulses f; a complementary f makes it −½ fᵀA f.
  auto dissipates = [&](const Eigen::VectorXd& x) {
    const double work = b.dot(x);
    return !(work + 0.5 * x.dot(A * x) > 1e-12 * std::abs(work));
  };
  const bool exact = solve_lcp_pivoting(A, b, f, active, ridge_on_stall);
  if (dissipates(f) || (b.size() > kLargeLcpRows && symmetric(A))) return exact;
  const std::size_t n = static_cast<std::size_t>(b.size());
  // Then the same with the diagonal of 1e-10 of the largest one (see solve_lcp_pivoting): a
  // definite matrix, whose LCP has one solution that Dantzig's method reaches; then Lemke's.
  Eigen::MatrixXd ridged = A;
  ridged.diagonal().array() += 1e-10 * std::max(A.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  active.assign(n, 0);
  if (pivot(ridged, b, f, active) && dissipates(f)) return true;
  active.assign(n, 0);
  if (lemke(A, b, f, active) && dissipates(f)) return true;
  f = Eigen::VectorXd::Zero(b.size());
  projected_gauss_seidel(A, b, f);
  active.assign(n, 0);
  return false;
}

}  // namespace tumble
