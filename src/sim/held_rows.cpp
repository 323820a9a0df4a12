#include "held_rows.hpp"
#include "lcp.hpp"
#include "mprgp.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace tumble {
// Named, not anonymous: HeldRowsCache::Impl (declared in the header) holds them, and a member
// of an anonymous type in a class with linkage is an error under unity builds
// (-Wsubobject-linkage: held_rows.cpp is then an included file).
namespace held_rows_detail {

using Vec6 = Eigen::Matrix<double, 6, 1>;

// One unknown force of a guess: along `col` at contact `contact` (on b, its opposite on a), its
// row the relative acceleration along `row`; `slot` is its place in the normal (contact index)
// or tangential (row of the tangent block) answer.
struct Unknown {
  int contact = 0;
  Vec3 row, col;
  bool tangent = false;
  int slot = 0;
};

// How one side of a row sees its member: the row's measure of the member's acceleration
// (a 6-vector: linear, angular) and the member's acceleration per unit force of the column.
struct SideRow {
  int member = -1;
  Vec6 measure = Vec6::Zero(), response = Vec6::Zero();
};

}  // namespace held_rows_detail

namespace {

using held_rows_detail::SideRow;
using held_rows_detail::Unknown;
using held_rows_detail::Vec6;

// Refinements of a ridged solve (iterated Tikhonov): x <- x + (K + dI)^-1 (r - K x). Each takes
// the error in the range of K from its size e to e d/(lambda + d): the ridge alone leaves the
// split among dependent rows off by d/lambda_min (2e-6 relative on an 8-box tower), two more
// solves with the same factor take it to round-off.
constexpr int kRefinements = 3;


// A row's measure of a member's acceleration (linear a, angular α): sign · (row · (a + α × p))
// = sign · [row; p × row] · [a; α], p the lever of the point it constrains.
Vec6 measure_of(const Vec3& row, const Vec3& point_lever, double sign) {
  Vec6 r;
  r << sign * row, sign * point_lever.cross(row);
  return r;
}

// A unit force along col at lever r on a member: its acceleration [col / m; I⁻¹ (r × col)].
Vec6 response_of(const MassInfo& m, const Vec3& col, const Vec3& lever, double sign) {
  Vec6 r;
  r << sign * m.inv_m * col, sign * (m.Iinv * lever.cross(col));
  return r;
}

SideRow side_row(const HeldRows& h, const Unknown& u, int side) {
  const SideGeometry& g = side == 0 ? h.f->a[u.contact] : h.f->b[u.contact];
  SideRow s;
  if (g.member < 0) return s;
  const double sign = side == 0 ? -1.0 : 1.0;
  s.member = g.member;
  // A tangent row holds the slip of the touching points (a ball's too): its point is where the
  // force acts. A normal row constrains the material point (a ball's centre: lever zero).
  s.measure = measure_of(u.row, u.tangent ? g.lever : g.point_lever, sign);
  s.response = response_of((*h.m)[g.member], u.col, g.lever, sign);
  return s;
}

// One guess: the unknowns of the clamped normal rows and of the sticking contacts among them,
// solved for their rows at zero. Writes the forces and the members' accelerations they cause.
struct Guess {
  std::vector<Unknown> unknowns;
  Eigen::VectorXd force;
  std::vector<Vec6> accel;  // per member
  double largest = 0.0;     // the largest |A| entry of the guess's matrix
  double ridge = 0.0;       // the diagonal added to it
};

}  // namespace

// The last fresh symmetric guess: its unknowns, their rows and right-hand side, and the
// factorisation of its ridged matrix K. A guess whose unknowns are some of those, with the same
// rows to the bit, is that system with the others held at zero: u = y − Z (Zᵀ_R)⁻¹ y_R, where
// y = K⁻¹ r and Z = K⁻¹ E_R the columns of the unknowns R left out (bordering), which costs a
// solve per unknown left out instead of a factorisation.
struct HeldRowsCache::Impl {
  bool valid = false;
  std::vector<held_rows_detail::Unknown> unknowns;
  std::vector<std::array<held_rows_detail::SideRow, 2>> sides;
  Eigen::VectorXd rhs, y;
  std::vector<int> normal_index;   // contact -> its normal row's unknown, -1 where none
  std::vector<int> tangent_index;  // 2 contact + a -> its tangent row a's unknown, or -1
  std::vector<Eigen::VectorXd> z;                // K⁻¹ e_k, computed once k is left out
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::SparseMatrix<double> K;  // ridged
  double largest = 0.0, ridge = 0.0;
};

HeldRowsCache::HeldRowsCache() : impl(std::make_unique<Impl>()) {}
HeldRowsCache::~HeldRowsCache() = default;

HeldRowsCache& HeldRowsCache::group(const GroupKey& key) {
  for (auto& [k, cache] : groups_)
    if (k == key) return *cache;
  groups_.emplace_back(key, std::make_unique<HeldRowsCache>());
  return *groups_.back().second;
}

bool HeldRowsCache::unsettled(const std::vector<int>& sticking,
                              const std::vector<char>& sliding) const {
  for (const auto& [st, sl] : unsettled_)
    if (st == sticking && sl == sliding) return true;
  return false;
}

void HeldRowsCache::remember_unsettled(const std::vector<int>& sticking,
                                       const std::vector<char>& sliding) {
  if (unsettled(sticking, sliding)) return;
  if (unsettled_.size() >= 4) unsettled_.erase(unsettled_.begin());
  unsettled_.emplace_back(sticking, sliding);
}

namespace {

bool same(const SideRow& a, const SideRow& b) {
  return a.member == b.member && a.measure == b.measure && a.response == b.response;
}

// Where the cached factorisation solves this guess (its unknowns a subset of the cached ones,
// rows identical), the forces from it.
bool solve_from_cache(HeldRowsCache::Impl& c, const std::vector<std::array<SideRow, 2>>& sides,
                      const Eigen::VectorXd& rhs, Guess& g) {
  if (!c.valid) return false;
  const int u = static_cast<int>(g.unknowns.size());
  std::vector<int> at(static_cast<std::size_t>(u));
  std::vector<char> kept(c.unknowns.size(), 0);
  for (int k = 0; k < u; ++k) {
    const Unknown& q = g.unknowns[static_cast<std::size_t>(k)];
    const std::vector<int>& index = q.tangent ? c.tangent_index : c.normal_index;
    const int key = q.tangent ? 2 * q.contact + (q.slot & 1) : q.slot;
    if (key >= static_cast<int>(index.size())) return false;
    const int j = index[static_cast<std::size_t>(key)];
    if (j < 0 || rhs(k) != c.rhs(j) || !same(sides[k][0], c.sides[j][0]) ||
        !same(sides[k][1], c.sides[j][1]) || c.unknowns[j].col != q.col || c.unknowns[j].row != q.row) {
      return false;
    }
    at[static_cast<std::size_t>(k)] = j;
    kept[static_cast<std::size_t>(j)] = 1;
  }
  std::vector<int> out;
  for (std::size_t j = 0; j < kept.size(); ++j)
    if (!kept[j]) out.push_back(static_cast<int>(j));
  // The reduced system's solve: d = K⁻¹ r − Z C⁻¹ (K⁻¹ r)_R, r zero on the rows left out.
  const int r = static_cast<int>(out.size());
  Eigen::LDLT<Eigen::MatrixXd> C;
  if (r > 0) {
    Eigen::MatrixXd Cm(r, r);
    for (int a = 0; a < r; ++a) {
      Eigen::VectorXd& z = c.z[static_cast<std::size_t>(out[a])];
      if (z.size() == 0) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(c.y.size());
        e(out[a]) = 1.0;
        z = c.ldlt.solve(e);
      }
    }
    for (int a = 0; a < r; ++a)
      for (int b = 0; b < r; ++b) Cm(a, b) = c.z[static_cast<std::size_t>(out[b])](out[a]);
    C.compute(Cm);
  }
  auto reduced = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd d = y;
    if (r == 0) return d;
    Eigen::VectorXd yr(r);
    for (int a = 0; a < r; ++a) yr(a) = y(out[a]);
    const Eigen::VectorXd mu = C.solve(yr);
    for (int b = 0; b < r; ++b) d -= mu(b) * c.z[static_cast<std::size_t>(out[b])];
    return d;
  };
  Eigen::VectorXd full = reduced(c.y);
  for (int it = 0; it < kRefinements; ++it) {
    // r − K x over the kept rows, K unridged: (K + δI) x − δ x.
    Eigen::VectorXd res = c.rhs - (c.K * full - c.ridge * full);
    for (int j : out) res(j) = 0.0;
    full += reduced(c.ldlt.solve(res));
  }
  for (int k = 0; k < u; ++k) g.force(k) = full(at[static_cast<std::size_t>(k)]);
  g.largest = c.largest;
  g.ridge = c.ridge;
  return g.force.allFinite();
}

bool solve_guess(const HeldRows& h, const std::vector<char>& clamped,
                 const std::vector<char>& loose, Guess& g, HeldRowsCache::Impl* cache) {
  const int n = static_cast<int>(h.b.size());
  g.unknowns.clear();
  for (int i = 0; i < n; ++i)
    if (clamped[static_cast<std::size_t>(i)])
      g.unknowns.push_back({i, h.f->frame[i].n, (*h.dir)[i], false, i});
  for (std::size_t j = 0; j < h.sticking.size(); ++j)
    if (clamped[static_cast<std::size_t>(h.sticking[j])] &&
        !loose[static_cast<std::size_t>(h.sticking[j])])
      for (int a = 0; a < 2; ++a) {
        const Vec3& t = h.t[2 * j + static_cast<std::size_t>(a)];
        g.unknowns.push_back({h.sticking[j], t, t, true, 2 * static_cast<int>(j) + a});
      }
  const int u = static_cast<int>(g.unknowns.size());
  const std::size_t members = h.m->size();
  g.accel.assign(members, Vec6::Zero());
  g.force = Eigen::VectorXd::Zero(u);
  g.largest = 0.0;
  if (u == 0) return true;
  std::vector<std::array<SideRow, 2>> sides(static_cast<std::size_t>(u));
  Eigen::VectorXd rhs(u);
  bool symmetric = true;
  for (int k = 0; k < u; ++k) {
    const Unknown& q = g.unknowns[static_cast<std::size_t>(k)];
    symmetric &= q.row == q.col;
    rhs(k) = -(q.tangent ? h.bt(q.slot) : h.b(q.slot));
    for (int side = 0; side < 2; ++side) sides[static_cast<std::size_t>(k)][side] = side_row(h, q, side);
  }
  if (!(symmetric && cache && solve_from_cache(*cache, sides, rhs, g))) {
    // Per member, the rows that see it: A(r, c) sums measure_r · response_c over the members
    // both rows touch, so an island's matrix has an entry only where two contacts share a body.
    std::vector<std::vector<int>> by_member(members);
    for (int k = 0; k < u; ++k)
      for (const SideRow& s : sides[static_cast<std::size_t>(k)])
        if (s.member >= 0) by_member[static_cast<std::size_t>(s.member)].push_back(k);
    auto side_on = [&](int k, int member) -> const SideRow& {
      const auto& two = sides[static_cast<std::size_t>(k)];
      return two[0].member == member ? two[0] : two[1];
    };
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t k = 0; k < members; ++k)
      for (int r : by_member[k])
        for (int c : by_member[k])
          entries.emplace_back(r, c, side_on(r, static_cast<int>(k)).measure.dot(
                                         side_on(c, static_cast<int>(k)).response));
    Eigen::SparseMatrix<double> A(u, u);
    A.setFromTriplets(entries.begin(), entries.end());
    double diag = 0.0;
    for (int k = 0; k < A.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
        g.largest = std::max(g.largest, std::abs(it.value()));
        if (it.row() == it.col()) diag = std::max(diag, std::abs(it.value()));
      }
    g.ridge = 1e-8 * std::max(diag, 1e-300);
    for (int k = 0; k < u; ++k) A.coeffRef(k, k) += g.ridge;
    if (symmetric) {
      HeldRowsCache::Impl local;
      HeldRowsCache::Impl& c = cache ? *cache : local;
      c.valid = false;
      c.ldlt.compute(A);
      if (c.ldlt.info() != Eigen::Success) return false;
      g.force = c.ldlt.solve(rhs);
      const Eigen::VectorXd plain = g.force;  // K⁻¹ r, ridged: what bordering starts from
      for (int it = 0; it < kRefinements; ++it)
        g.force += c.ldlt.solve(rhs - (A * g.force - g.ridge * g.force));
      if (cache) {
        c.valid = true;
        c.unknowns = g.unknowns;
        c.sides = sides;
        c.rhs = rhs;
        c.y = plain;
        c.K = A;
        c.largest = g.largest;
        c.ridge = g.ridge;
        c.z.assign(static_cast<std::size_t>(u), Eigen::VectorXd());
        c.normal_index.assign(static_cast<std::size_t>(n), -1);
        c.tangent_index.assign(2 * static_cast<std::size_t>(n), -1);
        for (int k = 0; k < u; ++k) {
          const Unknown& q = g.unknowns[static_cast<std::size_t>(k)];
          if (q.tangent)
            c.tangent_index[2 * static_cast<std::size_t>(q.contact) + (q.slot & 1)] = k;
          else
            c.normal_index[static_cast<std::size_t>(q.slot)] = k;
        }
      }
    } else {
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
      lu.analyzePattern(A);
      lu.factorize(A);
      if (lu.info() != Eigen::Success) return false;
      g.force = lu.solve(rhs);
      for (int it = 0; it < kRefinements; ++it)
        g.force += lu.solve(rhs - (A * g.force - g.ridge * g.force));
    }
    if (!g.force.allFinite()) return false;
  }
  for (int k = 0; k < u; ++k)
    for (const SideRow& s : sides[static_cast<std::size_t>(k)])
      if (s.member >= 0) g.accel[static_cast<std::size_t>(s.member)] += g.force(k) * s.response;
  return true;
}

// The relative acceleration along `row` of contact i's points with the guess's forces, less
// the free part.
double forced(const HeldRows& h, const Guess& g, int i, const Vec3& row, bool tangent) {
  double w = 0.0;
  for (int side = 0; side < 2; ++side) {
    const SideGeometry& s = side == 0 ? h.f->a[i] : h.f->b[i];
    if (s.member < 0) continue;
    w += measure_of(row, tangent ? s.lever : s.point_lever, side == 0 ? -1.0 : 1.0)
             .dot(g.accel[static_cast<std::size_t>(s.member)]);
  }
  return w;
}

enum class Verdict { Solved, Changed, Failed };

// Guesses tried before the dense solve takes over.
constexpr int kMaxRounds = 16;

// Checks a solved guess against the LCP; where it is not a solution, `next` is the block
// pivot (clamped rows with a negative force freed, violated free rows clamped).
Verdict check(const HeldRows& h, const Guess& g, const std::vector<char>& clamped, double tol_w,
              std::vector<char>& next, Eigen::VectorXd& w) {
  const int n = static_cast<int>(h.b.size());
  // The ridge moves every row by up to its diagonal times the forces, and the forces by about
  // as much relative to their size: rows and forces that near zero count as zero (else the
  // pivots cycle on a row that carries nothing and does not move, clamping and freeing it).
  const double largest_force = g.force.size() ? g.force.cwiseAbs().maxCoeff() : 0.0;
  const double tol_f = std::max(tol_w / std::max(g.largest, 1e-300), 1e-8 * largest_force);
  const double tol_free = std::max(tol_w, 10.0 * g.ridge * largest_force);
  next = clamped;
  bool changed = false, off = false;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < g.unknowns.size(); ++k) {
    const Unknown& q = g.unknowns[k];
    if (q.tangent) {
      const double wt = h.bt(q.slot) + forced(h, g, q.contact, q.row, true);
      off |= !(std::abs(wt) <= 1e3 * tol_w);
    } else {
      x(q.slot) = g.force(static_cast<Eigen::Index>(k));
    }
  }
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    w(i) = h.b(i) + forced(h, g, i, h.f->frame[i].n, false);
    if (clamped[static_cast<std::size_t>(i)]) {
      if (x(i) < -tol_f) {
        next[static_cast<std::size_t>(i)] = 0, changed = true;
      } else {
        off |= !(std::abs(w(i)) <= 1e3 * tol_w);
      }
    } else if (w(i) < -tol_free) {
      next[static_cast<std::size_t>(i)] = 1, changed = true;
    }
  }
  if (changed) return Verdict::Changed;
  return off ? Verdict::Failed : Verdict::Solved;
}

void write_answer(const HeldRows& h, const Guess& g, Eigen::VectorXd& normal,
                  Eigen::VectorXd& tangential) {
  normal = Eigen::VectorXd::Zero(h.b.size());
  tangential = Eigen::VectorXd::Zero(h.bt.size());
  for (std::size_t k = 0; k < g.unknowns.size(); ++k) {
    const Unknown& q = g.unknowns[k];
    const double x = g.force(static_cast<Eigen::Index>(k));
    if (q.tangent)
      tangential(q.slot) = x;
    else
      normal(q.slot) = std::max(x, 0.0);
  }
}

// The normal rows alone (the problem without static friction, symmetric where no contact
// slides) as a bound-constrained convex quadratic program: minimise q(x) = ½ xᵀ(A + ρI)x + bᵀx
// over x >= 0, whose gradient A x + b + ρx is the rows' accelerations w. Its minimiser solves the
// ridged LCP (ρ: the sparse guesses' ridge, 1e-8 of A's largest diagonal), uniquely. Solved by
// MPRGP (Dostál, "Optimal Quadratic Programming Algorithms", 2009, ch. 5: conjugate gradients
// on the rows that press, expansion steps that clamp many rows at once, proportioning steps that
// free many at once), with products by A taken through the members' accelerations, as A's
// entries are only where two rows share a body. Block pivots from a poor start can wander (a
// struck 10-row pyramid's 557 contacts: still 100–260 rows changing after 32 rounds, from the
// last clamped set or from 400 sweeps of projected Gauss–Seidel).
class NormalQp {
 public:
  explicit NormalQp(const HeldRows& h) : h_(h), n_(static_cast<int>(h.b.size())) {
    sides_.resize(static_cast<std::size_t>(n_));
    diag_ = Eigen::VectorXd::Zero(n_);
    std::vector<std::vector<int>> by_member(h.m->size());
    for (int i = 0; i < n_; ++i) {
      const Unknown u{i, h.f->frame[static_cast<std::size_t>(i)].n,
                      (*h.dir)[static_cast<std::size_t>(i)], false, i};
      auto& two = sides_[static_cast<std::size_t>(i)];
      two = {side_row(h, u, 0), side_row(h, u, 1)};
      for (const SideRow& r : two)
        if (r.member >= 0) {
          diag_(i) += r.measure.dot(r.response);
          by_member[static_cast<std::size_t>(r.member)].push_back(i);
        }
    }
    ridge_ = 1e-8 * std::max(diag_.maxCoeff(), 1e-300);
    // Solved in y = D^½ x, D the diagonal of A + ρI (Jacobi scaling: a 50 kg ball's rows and a
    // 1 kg box's then weigh alike); the bounds stay y >= 0.
    scale_.resize(n_);
    for (int i = 0; i < n_; ++i) scale_(i) = diag_(i) > 0.0 ? 1.0 / std::sqrt(diag_(i) + ridge_) : 0.0;
    // A bound on the scaled |A + ρI| (Gershgorin: the largest row sum of |entries|), for the
    // expansion steps' length ᾱ <= 2 / |A|.
    Eigen::VectorXd row_sum = ridge_ * scale_.cwiseAbs2();
    for (std::size_t k = 0; k < by_member.size(); ++k)
      for (int r : by_member[k])
        for (int c : by_member[k])
          row_sum(r) += scale_(r) * scale_(c) *
                        std::abs(on(r, static_cast<int>(k)).measure.dot(
                            on(c, static_cast<int>(k)).response));
    step_ = 1.0 / std::max(row_sum.maxCoeff(), 1e-300);
    acc_.assign(h.m->size(), Vec6::Zero());
  }

  // out = D^-½ (A + ρI) D^-½ y.
  void times(const Eigen::VectorXd& y, Eigen::VectorXd& out) {
    std::fill(acc_.begin(), acc_.end(), Vec6::Zero());
    for (int i = 0; i < n_; ++i)
      if (y(i) != 0.0)
        for (const SideRow& r : sides_[static_cast<std::size_t>(i)])
          if (r.member >= 0)
            acc_[static_cast<std::size_t>(r.member)] += scale_(i) * y(i) * r.response;
    out.resize(n_);
    for (int i = 0; i < n_; ++i) {
      double v = ridge_ * scale_(i) * y(i);
      for (const SideRow& r : sides_[static_cast<std::size_t>(i)])
        if (r.member >= 0) v += r.measure.dot(acc_[static_cast<std::size_t>(r.member)]);
      out(i) = scale_(i) * v;
    }
  }

  // Minimises from `force` (the rows' forces) until every row's projected gradient is within
  // tol in the rows' units (w), or `iterations` run out; returns the largest reached.
  double minimise(Eigen::VectorXd& force, double tol, int iterations) {
    Eigen::VectorXd x(n_), unit(n_);  // scaled: x = D^½ force
    for (int i = 0; i < n_; ++i) {
      x(i) = scale_(i) > 0.0 ? force(i) / scale_(i) : 0.0;
      unit(i) = scale_(i) > 0.0 ? 1.0 / scale_(i) : 0.0;
    }
    const double reached = minimise_bounded_qp(
        [this](const Eigen::VectorXd& y, Eigen::VectorXd& out) { times(y, out); },
        scale_.cwiseProduct(h_.b), unit, step_, x, tol, iterations);
    force = scale_.cwiseProduct(x);
    return reached;
  }

 private:
  const SideRow& on(int row, int member) const {
    const auto& two = sides_[static_cast<std::size_t>(row)];
    return two[0].member == member ? two[0] : two[1];
  }

  const HeldRows& h_;
  int n_;
  std::vector<std::array<SideRow, 2>> sides_;
  Eigen::VectorXd diag_, scale_;
  double ridge_ = 0.0, step_ = 0.0;
  std::vector<Vec6> acc_;
};

// MPRGP's iterations for a start of the block pivots, or for the answer where they do not
// settle.
constexpr int kQpIterations = 4000;

// The minimiser of the normal rows' quadratic program from zero; its largest projected
// gradient. Out of line: inlined into solve_held_rows_sparse, GCC 12 reports Eigen's frees
// there as used after free (-Wuse-after-free), falsely.
[[gnu::noinline]] double minimise_normal_rows(const HeldRows& h, double tol, Eigen::VectorXd& x) {
  NormalQp qp(h);
  x = Eigen::VectorXd::Zero(h.b.size());
  return qp.minimise(x, tol, kQpIterations);
}

}  // namespace

bool solve_held_rows_sparse(const HeldRows& h, std::vector<char>& active, Eigen::VectorXd& normal,
                            Eigen::VectorXd& tangential, HeldRowsCache* cache,
                            double* iterative_residual) {
  HeldRowsCache::Impl* c = cache ? cache->impl.get() : nullptr;
  if (iterative_residual) *iterative_residual = 0.0;
  const std::size_t n = static_cast<std::size_t>(h.b.size());
  if (active.size() != n) active.assign(n, 1);
  double scale = h.b.size() ? h.b.cwiseAbs().maxCoeff() : 0.0;
  if (h.bt.size()) scale = std::max(scale, h.bt.cwiseAbs().maxCoeff());
  const double tol_w = 1e-9 * std::max(scale, 1e-300);
  // A problem with tangent rows whose pivots did not settle at the last state (a sticking
  // contact that pulls when held and sinks when free: its mode, fixed at the stretch's start,
  // has no answer) is not tried again at the next: hold_or_slip's rounds and the stretch's
  // evaluations ask it at nearby states, each time for 16 rounds of factorisations in vain.
  std::vector<char> sliding(n, 0);
  for (std::size_t i = 0; i < n; ++i) sliding[i] = (*h.dir)[i] != h.f->frame[i].n;
  if (cache && !h.sticking.empty() && cache->unsettled(h.sticking, sliding)) return false;
  std::vector<char> clamped = active, next;
  // No clamped row to start from (a new set of contacts, or a last solve that found none) while
  // some row is pressed: all of them clamped, the dense solve's first guess too.
  if (std::find(clamped.begin(), clamped.end(), 1) == clamped.end() && (h.b.array() < 0.0).any())
    clamped.assign(n, 1);
  Guess g;
  Eigen::VectorXd w;
  // Block pivots while they make progress (fewer rows to change than the best so far within 3
  // rounds); after that one row at a time, the first of those to change (Murty's least-index
  // rule; Júdice and Pires' safeguard: block pivoting alone can cycle).
  std::size_t best = n + 1;
  int stalled = 0;
  // A sticking contact that pulls when clamped (its tangent rows with it) and sinks when free
  // has no answer in its mode at this state: it slips as it presses, which the modes fixed at
  // the stretch's start (hold_or_slip) do not know. Freed a second time in single pivots, it
  // is clamped without its tangent rows (pressing without friction, as the dense solve's
  // answer has it when its pressing set and its normal LCP still disagree).
  std::vector<char> loose(n, 0);
  std::vector<int> freed(n, 0);
  // Without static friction in the problem, MPRGP's minimiser of the ridged quadratic program
  // (NormalQp): the pivots' second start, and the answer where they do not settle from it.
  bool qp = false;
  Eigen::VectorXd x_qp;
  double qp_reached = INFINITY;
  auto iterative = [&]() -> bool {
    if (!qp || !iterative_residual) return false;
    normal = x_qp;
    tangential = Eigen::VectorXd::Zero(h.bt.size());
    for (std::size_t i = 0; i < n; ++i) active[i] = x_qp(static_cast<Eigen::Index>(i)) > 0.0;
    *iterative_residual = qp_reached / std::max(scale, 1e-300);
    return true;
  };
  for (int round = 0; round < 2 * kMaxRounds; ++round) {
    // Not settled from the last clamped set: once, where there are no tangent rows, the pivots
    // start again from the rows that press in the quadratic program's minimiser.
    if (round == kMaxRounds) {
      if (!h.sticking.empty()) break;
      bool symmetric = true;
      for (std::size_t i = 0; i < n; ++i) symmetric &= (*h.dir)[i] == h.f->frame[i].n;
      if (!symmetric) break;  // sliding friction: A unsymmetric, no quadratic program
      qp = true;
      qp_reached = minimise_normal_rows(h, tol_w, x_qp);
      for (std::size_t i = 0; i < n; ++i) clamped[i] = x_qp(static_cast<Eigen::Index>(i)) > 0.0;
      best = n + 1, stalled = 0;
      std::fill(freed.begin(), freed.end(), 0);
    }
    if (!solve_guess(h, clamped, loose, g, c)) return iterative();
    const Verdict v = check(h, g, clamped, tol_w, next, w);
    if (v == Verdict::Failed) return iterative();
    if (v == Verdict::Changed) {
      std::size_t changes = 0;
      for (std::size_t i = 0; i < n; ++i) changes += next[i] != clamped[i];
      if (changes < best && stalled < 3) {
        best = changes, stalled = 0;
      } else if (++stalled >= 3) {
        for (std::size_t i = 0; i < n; ++i)
          if (next[i] != clamped[i]) {
            if (!next[i] && ++freed[i] >= 2 && !loose[i]) {
              loose[i] = 1;  // stays clamped, its tangent rows dropped
              break;
            }
            clamped[i] = next[i];
            break;
          }
        continue;
      }
      clamped.swap(next);
      continue;
    }
    write_answer(h, g, normal, tangential);
    // Rows free at w = 0 (a contact that carries nothing and does not move away) leave the
    // split among dependent rows to the pivoting: a domino's edge held by one end or both.
    // As the dense solve does (canonical_split), they join the clamped set where the answer
    // with them is still a solution, so that a symmetric pose is held symmetrically.
    std::vector<char> with = clamped;
    bool degenerate = false;
    for (std::size_t i = 0; i < n; ++i)
      if (!clamped[i] && std::abs(w(static_cast<Eigen::Index>(i))) <= tol_w) with[i] = 1, degenerate = true;
    if (degenerate && solve_guess(h, with, loose, g, c) &&
        check(h, g, with, tol_w, next, w) == Verdict::Solved) {
      write_answer(h, g, normal, tangential);
      clamped.swap(with);
    }
    active = clamped;
    return true;
  }
  if (cache && !h.sticking.empty()) cache->remember_unsettled(h.sticking, sliding);
  return iterative();
}

Eigen::VectorXd least_norm_solve(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs) {
  const Eigen::Index n = M.rows();
  if (n > kSparseRows) {
    Eigen::SparseMatrix<double> S = M.sparseView();
    const double diag = std::max(M.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    for (Eigen::Index k = 0; k < n; ++k) S.coeffRef(k, k) += 1e-8 * diag;
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(S);
    if (ldlt.info() == Eigen::Success) {
      Eigen::VectorXd x = ldlt.solve(rhs);
      for (int it = 0; it < kRefinements; ++it) x += ldlt.solve(rhs - M * x);
      if (x.allFinite()) return x;
    }
  }
  // A contact matrix goes to the pivoted LDLᵀ (lcp.hpp): an impact's friction over a pile's
  // contacts had spent a quarter of 27 dice's run in a complete orthogonal decomposition here.
  return least_norm(M, rhs, static_cast<double>(n) * Eigen::NumTraits<double>::epsilon());
}

Eigen::VectorXd block_least_norm(const Eigen::MatrixXd& M, const Eigen::VectorXd& rhs,
                                 const std::vector<int>& group) {
  const Eigen::Index n = M.rows();
  int blocks = 0;
  for (int g : group) blocks = std::max(blocks, g + 1);
  if (blocks <= 1) return least_norm_solve(M, rhs);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<std::vector<Eigen::Index>> rows(static_cast<std::size_t>(blocks));
  for (Eigen::Index r = 0; r < n; ++r) rows[static_cast<std::size_t>(group[r])].push_back(r);
  for (const std::vector<Eigen::Index>& b : rows) {
    const auto q = static_cast<Eigen::Index>(b.size());
    if (q == 0) continue;  // a subset of the rows (stop_points) may leave a block out
    Eigen::MatrixXd Mb(q, q);
    Eigen::VectorXd rb(q);
    for (Eigen::Index i = 0; i < q; ++i) {
      rb(i) = rhs(b[i]);
      for (Eigen::Index j = 0; j < q; ++j) Mb(i, j) = M(b[i], b[j]);
    }
    const Eigen::VectorXd xb = least_norm_solve(Mb, rb);
    for (Eigen::Index i = 0; i < q; ++i) x(b[i]) = xb(i);
  }
  return x;
}

}  // namespace tumble
