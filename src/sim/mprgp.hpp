#pragma once
// A bound-constrained convex quadratic program, min q(x) = ½ xᵀM x + bᵀx over x >= 0, whose
// minimiser solves the linear complementarity problem x >= 0, w = M x + b >= 0, xᵀw = 0 of a
// symmetric positive definite M. Solved by MPRGP (Dostál, "Optimal Quadratic Programming
// Algorithms", 2009, ch. 5): conjugate gradients on the rows that press, expansion steps that
// clamp many rows at once, proportioning steps that free many at once. It needs only products
// by M, so a large island's contact rows (M's entries only where two rows share a body) cost
// in proportion to their count, and it decreases q at every step: from x = 0, where q is an
// impact's change of kinetic energy, it never gains energy, converged or not.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace tumble {

/// Minimises q from x (projected onto x >= 0) until every row's projected gradient (a pressing
/// row's |w|, a free row's −w) times unit(i) is within tol, or `iterations` run out; returns the
/// largest such value reached. `times(y, out)` writes out = M y; `step` is the expansion steps'
/// length, at most 2 / |M|. Rows with unit(i) = 0 stay at zero (no row: both sides static).
template <class Times>
double minimise_bounded_qp(Times&& times, const Eigen::VectorXd& b, const Eigen::VectorXd& unit,
                           double step, Eigen::VectorXd& x, double tol, int iterations) {
  const Eigen::Index n = b.size();
  for (Eigen::Index i = 0; i < n; ++i) x(i) = unit(i) > 0.0 ? std::max(x(i), 0.0) : 0.0;
  Eigen::VectorXd g, p, Ap, phi(n), beta(n);
  times(x, g);
  g += b;
  // The free and chopped gradients (φ on the rows that press, β = min(w, 0) on the others).
  auto split = [&]() -> double {
    double worst = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool row = unit(i) > 0.0;
      phi(i) = row && x(i) > 0.0 ? g(i) : 0.0;
      beta(i) = row && x(i) <= 0.0 ? std::min(g(i), 0.0) : 0.0;
      worst = std::max(worst, std::max(std::abs(phi(i)), -beta(i)) * unit(i));
    }
    return worst;
  };
  double reached = split();
  p = phi;
  for (int it = 0; it < iterations && reached > tol; ++it) {
    // Proportional: the rows that could be freed (β) matter less than the progress left on the
    // pressing ones (φ̃: φ cut to what a step of `step` takes before a force reaches zero).
    double reduced = 0.0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (x(i) > 0.0) reduced += std::min(x(i) / step, phi(i)) * phi(i);
    if (beta.squaredNorm() <= reduced) {
      times(p, Ap);
      const double pAp = p.dot(Ap);
      if (!(pAp > 0.0)) break;
      const double a_cg = g.dot(p) / pAp;
      double a_f = INFINITY;
      for (Eigen::Index i = 0; i < n; ++i)
        if (p(i) > 0.0) a_f = std::min(a_f, x(i) / p(i));
      if (a_cg <= a_f) {  // a conjugate gradient step that stays in x >= 0
        x -= a_cg * p;
        g -= a_cg * Ap;
        x = x.cwiseMax(0.0);
        reached = split();
        p = phi - (phi.dot(Ap) / pAp) * p;
      } else {  // expansion: to the bound, then a projected gradient step
        x = (x - a_f * p).cwiseMax(0.0);
        g -= a_f * Ap;
        split();
        x = (x - step * phi).cwiseMax(0.0);
        times(x, g);
        g += b;
        reached = split();
        p = phi;
      }
    } else {  // proportioning: the rows whose w < 0 freed together
      times(beta, Ap);
      const double dAd = beta.dot(Ap);
      if (!(dAd > 0.0)) break;
      const double a = g.dot(beta) / dAd;
      x -= a * beta;
      g -= a * Ap;
      reached = split();
      p = phi;
    }
    if (it % 64 == 63) {  // the recurrence's drift, against the gradient recomputed
      times(x, g);
      g += b;
      reached = split();
    }
  }
  return reached;
}

}  // namespace tumble
