#include "floor_contact.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "lcp.hpp"
#include "support_polygon.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

double kinetic_energy(const RigidBody& b) {
  return b.energy(Vec3::Zero());
}

Vec3 point_velocity(const RigidBody& b, const Vec3& omega, const Vec3& r) {
  return b.velocity() + omega.cross(r);
}

void apply_impulse(RigidBody& b, const Vec3& r, const Vec3& impulse) {
  b.state.P += impulse;
  if (!b.is_particle()) b.state.L += r.cross(impulse);
}

}  // namespace

double min_gap(const RigidBody& b, const BodyState& s, double floor_height, const ContactSet& set) {
  double lowest = INFINITY;
  for (int i : set.indices()) lowest = std::min(lowest, vertex_gap(b, s, i, floor_height));
  return lowest;
}

double min_gap(const RigidBody& b, const BodyState& s, double floor_height,
               const std::vector<int>& set) {
  double lowest = INFINITY;
  for (int i : set) lowest = std::min(lowest, vertex_gap(b, s, i, floor_height));
  return lowest;
}

void vertices_below(const RigidBody& b, const BodyState& s, double floor_height,
                    const ContactSet& skip, std::vector<int>& below) {
  below.clear();
  const auto held = skip.indices();
  const int n = static_cast<int>(b.vertices().size());
  for (int i = 0; i < n; ++i) {
    if (std::find(held.begin(), held.end(), i) != held.end()) continue;
    if (vertex_gap(b, s, i, floor_height) < 0.0) below.push_back(i);
  }
}

double approach_speed(const RigidBody& b, const ContactSet& c) {
  const Vec3 omega = b.angular_velocity();
  double fastest = 0.0;
  for (int i : c.indices())
    fastest = std::max(fastest, -point_velocity(b, omega, b.vertex_offset(b.state.R, i)).y());
  return fastest;
}

double lowest_gap(const RigidBody& b, const BodyState& s, double floor_height) {
  double lowest = INFINITY;
  const int n = static_cast<int>(b.vertices().size());
  for (int i = 0; i < n; ++i) lowest = std::min(lowest, vertex_gap(b, s, i, floor_height));
  return lowest;
}

void reduce_to_support(const RigidBody& b, const std::vector<int>& candidates, ContactSet& out) {
  out.count = 0;
  if (static_cast<int>(candidates.size()) <= ContactSet::kMaxPoints) {
    for (int i : candidates) out.vertex[out.count++] = i;
    return;
  }
  // The candidates seen from above (x, z), and the corners of their support polygon.
  std::vector<PlanePoint> points;
  points.reserve(candidates.size());
  for (int i : candidates) {
    const Vec3 w = b.vertex_offset(b.state.R, i);
    points.push_back({w.x(), w.z(), i});
  }
  std::vector<PlanePoint> hull(2 * points.size() + 1);
  hull.resize(static_cast<std::size_t>(
      support_polygon(points.data(), static_cast<int>(points.size()), hull.data())));
  if (static_cast<int>(hull.size()) <= ContactSet::kMaxPoints) {
    for (const PlanePoint& h : hull) out.vertex[out.count++] = h.index;
    return;
  }
  // More corners than the LCP takes: keep the corner extreme in each of 8 directions 45° apart
  // (duplicates dropped), which keeps the support polygon up to its finest corners.
  for (int d = 0; d < 8; ++d) {
    const double angle = d * (kPi / 4.0);
    const double cx = std::cos(angle), cz = std::sin(angle);
    const PlanePoint* best = &hull[0];
    for (const PlanePoint& h : hull)
      if (h.x * cx + h.z * cz > best->x * cx + best->z * cz) best = &h;
    const auto chosen = out.indices();
    if (std::find(chosen.begin(), chosen.end(), best->index) == chosen.end())
      out.vertex[out.count++] = best->index;
  }
}

ContactSet touching_vertices(const RigidBody& b, double floor_height, double touch_m,
                             double rest_speed, Clearance* clearance) {
  ContactSet c;
  if (clearance) *clearance = Clearance{};
  c.floor_height = floor_height;
  const Vec3 omega = b.angular_velocity();
  const int n = static_cast<int>(b.vertices().size());
  int first[ContactSet::kMaxPoints];
  int found = 0;
  std::vector<int> many;  // only when a flat hull face puts more than kMaxPoints on the floor
  for (int i = 0; i < n; ++i) {
    const double gap = vertex_gap(b, b.state, i, floor_height);
    if (gap > touch_m) {
      if (clearance) clearance->lowest_m = std::min(clearance->lowest_m, gap);
      continue;
    }
    const Vec3 r = b.vertex_offset(b.state.R, i);
    if (std::abs(point_velocity(b, omega, r).y()) > rest_speed) {
      if (clearance) ++clearance->fast;
      continue;
    }
    if (found < ContactSet::kMaxPoints) {
      first[found++] = i;
    } else {
      if (many.empty()) many.assign(first, first + found);
      many.push_back(i);
    }
  }
  if (many.empty()) {
    for (int i = 0; i < found; ++i) c.vertex[c.count++] = first[i];
  } else {
    reduce_to_support(b, many, c);
  }
  return c;
}

ContactSet held_points(const RigidBody& b, const ContactSet& c, double hold_speed) {
  ContactSet held;
  held.floor_height = c.floor_height;
  const Vec3 omega = b.angular_velocity();
  for (int i = 0; i < c.count; ++i) {
    const Vec3 r = b.vertex_offset(b.state.R, c.vertex[i]);
    if (point_velocity(b, omega, r).y() <= hold_speed) held.vertex[held.count++] = c.vertex[i];
  }
  return held;
}

double resolve_impact(RigidBody& b, const ContactSet& c, double rest_speed, double mu,
                      double* normal_impulse) {
  const int n = c.count;
  const Vec3 omega = b.angular_velocity();
  Vec3 r[8];
  for (Vec3& ri : r) ri.setZero();  // only the first n are used
  LcpVector vn(n);
  bool approaching = false;
  for (int i = 0; i < n; ++i) {
    r[i] = b.vertex_offset(b.state.R, c.vertex[i]);
    vn(i) = point_velocity(b, omega, r[i]).y();
    approaching |= vn(i) < 0.0;
  }
  // No point approaches: zero impulses solve the LCP (and leave no friction to apply). The
  // common case of resting contact, which checks every stretch for a point still coming down.
  if (!approaching) {
    std::fill(normal_impulse, normal_impulse + n, 0.0);
    return 0.0;
  }
  const double e_before = kinetic_energy(b);
  const BodyState before = b.state;
  const Mat3 Iinv = b.inverse_inertia_world();
  LcpMatrix A;
  fill_contact_matrix(b.inverse_mass(), Iinv, r, n, A);

  // Newton's law per point: an approaching point leaves at >= e times its approach speed.
  auto solve = [&](bool elastic) {
    LcpVector rhs(n);
    for (int i = 0; i < n; ++i) {
      const bool bounces = elastic && vn(i) < -rest_speed;
      rhs(i) = vn(i) < 0.0 && bounces ? (1.0 + b.restitution()) * vn(i) : vn(i);
    }
    const LcpVector j = solve_lcp(A, rhs);
    for (int i = 0; i < n; ++i) {
      normal_impulse[i] = j(i);
      apply_impulse(b, r[i], j(i) * Vec3::UnitY());
    }
  };
  solve(true);
  // Simultaneous Newton restitution can, in rare configurations, return more energy than came
  // in; the inelastic solution is a projection in the kinetic metric and never does.
  if (kinetic_energy(b) > e_before * (1.0 + 1e-12)) {
    b.state = before;
    solve(false);
  }
  if (mu > 0.0) {
    apply_friction(b, c, normal_impulse, mu);
    // A tangential impulse at one point also moves the points along the normal (the body
    // turns): it can leave one approaching again, which a held contact would then carry into
    // the floor (and the lift out would gain m g times the depth). A last inelastic normal pass
    // stops every approach; it is a projection in the kinetic metric, so it only dissipates.
    // Impulses change P and L, not R: the points and the matrix are those of the first pass.
    const Vec3 w = b.angular_velocity();
    LcpVector again(n);
    bool approach = false;
    for (int i = 0; i < n; ++i) {
      again(i) = point_velocity(b, w, r[i]).y();
      approach |= again(i) < 0.0;
    }
    if (approach) {
      const LcpVector j = solve_lcp(A, again);
      for (int i = 0; i < n; ++i) {
        normal_impulse[i] += j(i);
        apply_impulse(b, r[i], j(i) * Vec3::UnitY());
      }
    }
  }
  return kinetic_energy(b) - e_before;
}

void apply_friction(RigidBody& b, const ContactSet& c, const double* normal_impulse, double mu) {
  using MatF = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 16, 16>;
  using VecF = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 16, 1>;
  const int n = c.count;
  if (n == 0) return;
  const Vec3 omega = b.angular_velocity();
  const Mat3 Iinv = b.inverse_inertia_world();
  Vec3 r[8];
  for (Vec3& ri : r) ri.setZero();  // only the first n are used
  VecF u(2 * n);                    // tangential slip (x, z) of every point
  for (int i = 0; i < n; ++i) {
    r[i] = b.vertex_offset(b.state.R, c.vertex[i]);
    const Vec3 vp = point_velocity(b, omega, r[i]);
    u.segment<2>(2 * i) << vp.x(), vp.z();
  }
  if (u.cwiseAbs().maxCoeff() == 0.0) return;
  // K maps tangential impulses at the points to changes of their tangential velocities.
  MatF K(2 * n, 2 * n);
  for (int j = 0; j < n; ++j)
    for (int a = 0; a < 2; ++a) {
      const Vec3 t = a == 0 ? Vec3::UnitX() : Vec3::UnitZ();
      const Vec3 dw = Iinv * r[j].cross(t);
      for (int i = 0; i < n; ++i) {
        const Vec3 dv = t * b.inverse_mass() + dw.cross(r[i]);
        K(2 * i, 2 * j + a) = dv.x();
        K(2 * i + 1, 2 * j + a) = dv.z();
      }
    }
  VecF t = -Eigen::CompleteOrthogonalDecomposition<MatF>(K).solve(u);
  bool sticks = true;
  for (int i = 0; i < n; ++i)
    if (t.segment<2>(2 * i).norm() > mu * normal_impulse[i] * (1.0 + 1e-9)) sticks = false;
  if (!sticks) {
    for (int i = 0; i < n; ++i) {
      const double slip = u.segment<2>(2 * i).norm();
      t.segment<2>(2 * i) =
          slip > 0.0 ? Eigen::Vector2d(-mu * normal_impulse[i] * u.segment<2>(2 * i) / slip)
                     : Eigen::Vector2d::Zero();
    }
    // Kinetic energy along s·t is KE0 + s (u·t) + ½ s² tᵀKt: take the s in [0, 1] that
    // dissipates most, so sliding friction stops a slip but never reverses it.
    const double slope = u.dot(t), curvature = t.dot(K * t);
    if (slope >= 0.0) return;
    const double s = curvature > 0.0 ? std::min(1.0, -slope / curvature) : 1.0;
    t *= s;
  }
  for (int i = 0; i < n; ++i) apply_impulse(b, r[i], Vec3(t(2 * i), 0.0, t(2 * i + 1)));
}

void classify_sliding(const RigidBody& b, ContactSet& c, double mu, double dv) {
  c.friction = mu;
  const Vec3 omega = b.angular_velocity();
  // A ball's slip changes 1 + m r²/I = 7/2 times faster than its centre's speed under the same
  // friction (the force also spins it up): friction stops that much more slip in a stretch.
  if (b.is_sphere()) dv *= 1.0 + b.mass() * b.radius() * b.radius() / b.inertia_body().x();
  for (int i = 0; i < c.count; ++i) {
    Vec3 slip = point_velocity(b, omega, b.vertex_offset(b.state.R, c.vertex[i]));
    slip.y() = 0.0;
    c.sliding[i] = slip.norm() > 2.0 * mu * dv;
  }
}

double lift_out_of_floor(RigidBody& b, const ContactSet& c, double floor_height) {
  double deepest = 0.0;
  for (int i = 0; i < c.count; ++i)
    deepest = std::max(deepest, -vertex_gap(b, b.state, c.vertex[i], floor_height));
  b.state.x.y() += deepest;
  return deepest;
}

bool can_rest(const RigidBody& b, const ContactSet& c, const Vec3& gravity, double sleep_speed) {
  if (gravity.y() >= 0.0) return false;
  const Vec3 omega = b.angular_velocity();
  // A sphere touches the plane at one point straight below its centre: in equilibrium when
  // gravity points straight down (it rolls away otherwise).
  if (b.is_sphere())
    return c.count == 1 && gravity.x() == 0.0 && gravity.z() == 0.0 &&
           b.velocity().norm() + omega.norm() * b.radius() <= sleep_speed;
  if (c.count < 3) return false;
  double reach = 0.0;
  for (const Vec3& v : b.vertices()) reach = std::max(reach, v.norm());
  if (b.velocity().norm() + omega.norm() * reach > sleep_speed) return false;
  // The support polygon of the resting points seen from above: the centre of mass must lie
  // strictly inside it (by 1e-6 of each edge's length): on an edge the body could still tip.
  PlanePoint points[ContactSet::kMaxPoints], hull[2 * ContactSet::kMaxPoints + 1];
  for (int i = 0; i < c.count; ++i) {
    const Vec3 w = b.state.x + b.vertex_offset(b.state.R, c.vertex[i]);
    points[i] = {w.x(), w.z(), c.vertex[i]};
  }
  const int corners = support_polygon(points, c.count, hull);
  return strictly_inside(hull, corners, b.state.x.x(), b.state.x.z(), 1e-6);
}

}  // namespace tumble