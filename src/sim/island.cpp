#include "island.hpp"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <numeric>
#include <cmath>

#include "held_rows.hpp"
#include "integrator_schemes.hpp"
#include "lcp.hpp"

namespace tumble {

namespace {

bool round_side(const RigidBody* b) {
  return b && (b->shape() == ShapeKind::Sphere || b->shape() == ShapeKind::Particle);
}

Frames frames_of(const IslandView& v, const std::vector<IslandContact>& contacts,
                 const IslandState& s) {
  Frames f;
  const std::size_t n = contacts.size();
  f.frame.resize(n);
  f.a.resize(n);
  f.b.resize(n);
  f.round_pair.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const IslandContact& c = contacts[i];
    const IslandPair& p = v.island->pairs[c.pair];
    f.frame[i] = contact_frame(v, c, s);
    const bool ra = round_side(v.side_body(p.a)), rb = round_side(v.side_body(p.b));
    f.round_pair[i] = ra && rb;
    if (p.a.kind == Side::Member) {
      f.a[i].member = p.a.index;
      f.a[i].lever = f.frame[i].ra;
      f.a[i].point_lever = ra ? Vec3(Vec3::Zero()) : f.frame[i].ra;
    }
    f.b[i].member = p.b.index;
    f.b[i].lever = f.frame[i].rb;
    f.b[i].point_lever = rb ? Vec3(Vec3::Zero()) : f.frame[i].rb;
  }
  return f;
}

// The contacts in groups joined by the members they share (the floor and fixed bodies join
// none): a force or an impulse at one group's contacts moves no other group's points, so the
// contact matrix is block diagonal over them. Contact indices ascending; groups in the order of
// their first contact.
std::vector<std::vector<int>> contact_groups(const IslandView& v,
                                             const std::vector<IslandContact>& contacts) {
  std::vector<int> root(v.island->members.size());
  std::iota(root.begin(), root.end(), 0);
  auto at = [&](int x) -> int& { return root[static_cast<std::size_t>(x)]; };
  auto find = [&](int x) {
    while (at(x) != x) x = at(x) = at(at(x));
    return x;
  };
  for (const IslandContact& c : contacts) {
    const IslandPair& p = v.island->pairs[c.pair];
    if (p.a.kind == Side::Member) at(find(p.a.index)) = find(p.b.index);
  }
  std::vector<int> group_of_root(root.size(), -1);
  std::vector<std::vector<int>> groups;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const int b = v.island->pairs[contacts[i].pair].b.index;
    int& g = group_of_root[static_cast<std::size_t>(find(b))];
    if (g < 0) g = static_cast<int>(groups.size()), groups.emplace_back();
    groups[static_cast<std::size_t>(g)].push_back(static_cast<int>(i));
  }
  return groups;
}

// Each contact's group (contact_groups), with `rows` rows per contact.
std::vector<int> row_groups(const IslandView& v, const std::vector<IslandContact>& contacts,
                            int rows) {
  std::vector<int> of(contacts.size() * static_cast<std::size_t>(rows));
  const std::vector<std::vector<int>> groups = contact_groups(v, contacts);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (int i : groups[g])
      for (int r = 0; r < rows; ++r)
        of[static_cast<std::size_t>(rows * i + r)] = static_cast<int>(g);
  return of;
}

// Per member: inverse mass and world inverse inertia at s.
std::vector<MassInfo> masses(const IslandView& v, const IslandState& s) {
  std::vector<MassInfo> m(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    const RigidBody& b = v.member(static_cast<int>(k));
    m[k].inv_m = b.inverse_mass();
    if (b.is_particle()) {
      m[k].Iinv.setZero();
    } else {
      const Mat3 R = rotation_of(s[k], v.rotation);
      m[k].Iinv = R * b.inverse_inertia_body().asDiagonal() * R.transpose();
    }
  }
  return m;
}

// A_ij: the change of the normal (relative) velocity or acceleration at contact i per unit
// impulse or force at contact j along dir_j (on b, and its opposite on a).
Eigen::MatrixXd contact_matrix(const Frames& f, const std::vector<MassInfo>& m,
                               const std::vector<Vec3>& dir) {
  const int n = static_cast<int>(f.frame.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  // Each member's rows and sides, in row order: a unit impulse at j moves only the rows of its
  // own members (a heap's matrix is mostly zeros; scanning every row for them was 8 % of a
  // landing heap of a hundred dice). Entries (member, row, side), sorted.
  std::vector<std::array<int, 3>> rows_of;
  rows_of.reserve(static_cast<std::size_t>(2 * n));
  for (int i = 0; i < n; ++i)
    for (int side_i = 0; side_i < 2; ++side_i) {
      const SideGeometry& gi = side_i == 0 ? f.a[i] : f.b[i];
      if (gi.member >= 0) rows_of.push_back({gi.member, i, side_i});
    }
  std::sort(rows_of.begin(), rows_of.end());
  for (int j = 0; j < n; ++j) {
    // The velocity change of member k per unit impulse at j: (dv, dω).
    for (int side = 0; side < 2; ++side) {
      const SideGeometry& gj = side == 0 ? f.a[j] : f.b[j];
      if (gj.member < 0) continue;
      const double sign_j = side == 0 ? -1.0 : 1.0;
      const MassInfo& mk = m[gj.member];
      const Vec3 dv = sign_j * mk.inv_m * dir[j];
      const Vec3 dw = sign_j * (mk.Iinv * gj.lever.cross(dir[j]));
      const auto first = std::lower_bound(rows_of.begin(), rows_of.end(),
                                          std::array<int, 3>{gj.member, -1, -1});
      for (auto e = first; e != rows_of.end() && (*e)[0] == gj.member; ++e) {
        const int i = (*e)[1], side_i = (*e)[2];
        const SideGeometry& gi = side_i == 0 ? f.a[i] : f.b[i];
        const double sign_i = side_i == 0 ? -1.0 : 1.0;
        A(i, j) += sign_i * f.frame[i].n.dot(dv + dw.cross(gi.point_lever));
      }
    }
  }
  return A;
}

Vec3 side_velocity(const IslandView& v, const IslandState& s, const SideGeometry& g,
                   const Vec3& lever) {
  if (g.member < 0) return Vec3::Zero();
  const RigidBody& b = v.member(g.member);
  const Vec3 vel = s[g.member].P * b.inverse_mass();
  if (b.is_particle()) return vel;
  const Mat3 R = rotation_of(s[g.member], v.rotation);
  const Vec3 omega = R * b.inverse_inertia_body().asDiagonal() * R.transpose() * s[g.member].L;
  return vel + omega.cross(lever);
}

// Relative velocity of the contact's surface points, b minus a.
Vec3 relative_velocity(const IslandView& v, const IslandState& s, const Frames& f, int i) {
  return side_velocity(v, s, f.b[i], f.b[i].lever) - side_velocity(v, s, f.a[i], f.a[i].lever);
}

void apply(IslandState& s, const Frames& f, int i, const Vec3& impulse) {
  if (f.b[i].member >= 0) {
    s[f.b[i].member].P += impulse;
    s[f.b[i].member].L += f.b[i].lever.cross(impulse);
  }
  if (f.a[i].member >= 0) {
    s[f.a[i].member].P -= impulse;
    s[f.a[i].member].L -= f.a[i].lever.cross(impulse);
  }
}

// The direction a sliding contact slips: its tangential relative velocity, or where that is
// still below round-off of its start (sliding from rest), the direction it was found to go.
Vec3 slip_unit(const IslandContact& c, const ContactFrame& f, const Vec3& dv) {
  if (c.fixed_slip) return c.slip_direction;
  const Vec3 slip = dv - f.n * f.n.dot(dv);
  const double speed = slip.norm();
  if (speed > 1e-9 * std::max(dv.norm(), 1e-3) && speed > 0.0) return slip / speed;
  return c.slip_direction;
}

// Two unit tangents of n.
void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
  t1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  t2 = n.cross(t1);
}

}  // namespace

// Two edges closer to parallel than this (the sine of their angle, 0.06°) have no line square
// to both that is worth the name: an edge–edge contact turned that far (within a stretch, as
// the bodies turn) keeps the normal of the body it was found on and its material points.
constexpr double kEdgesCross = 1e-3;


ContactFrame contact_frame(const IslandView& v, const IslandContact& c, const IslandState& s) {
  const IslandPair& p = v.island->pairs[c.pair];
  ContactFrame f;
  const RigidBody* A = v.side_body(p.a);
  const RigidBody* B = v.side_body(p.b);
  const Vec3 xb = s[p.b.index].x;
  const Mat3 Rb = rotation_of(s[p.b.index], v.rotation);
  Vec3 xa = Vec3::Zero();
  Mat3 Ra = Mat3::Identity();
  if (p.a.kind == Side::Member) {
    xa = s[p.a.index].x;
    Ra = rotation_of(s[p.a.index], v.rotation);
  } else if (p.a.kind == Side::Fixed) {
    xa = A->state.x;
    Ra = A->state.R;
  }
  if (round_side(A) && round_side(B)) {
    const Vec3 d = xb - xa;
    f.n = d.norm() > 0.0 ? Vec3(d.normalized()) : Vec3(Vec3::UnitY());
  } else if (c.normal_on >= 0) {
    f.n = rotation_of(s[c.normal_on], v.rotation) * c.normal_local;
  } else {
    f.n = c.normal_local;
  }
  if (c.edge_edge) {
    // Two edges: the line between them is square to both, as they turn now. (The separating
    // axis test never picks edges closer to parallel than its face axes allow.)
    f.ea = Ra * c.edge_a_local;
    f.eb = Rb * c.edge_b_local;
    const Vec3 u = f.ea.cross(f.eb);
    if (u.norm() > kEdgesCross) f.n = c.edge_sign * u.normalized();
  }
  // Side a.
  if (round_side(A)) {
    f.ra = c.radius_a * f.n;
    f.pa = xa + f.ra;
    if (p.a.kind != Side::Member) f.ra.setZero();
  } else if (p.a.kind == Side::Member) {
    f.ra = Ra * c.anchor_a;
    f.pa = xa + f.ra;
  } else if (p.a.kind == Side::Fixed) {
    f.pa = xa + Ra * c.anchor_a;
    f.ra.setZero();
  } else {
    f.pa = c.anchor_a;
    f.ra.setZero();
  }
  // Side b (always a member).
  f.rb = round_side(B) ? Vec3(-c.radius_b * f.n) : Vec3(Rb * c.anchor_b);
  f.pb = xb + f.rb;
  // A point on a face that turns: the face's side touches where the other side's point is, its
  // nearest point on the face's plane, not the material point it touched at when the contact
  // was found. While the other side slides, that one moves along the face, and its velocity
  // misses the turn of the plane under the sliding point (ṅ·(p_b − p_a), 1e-4 m/s for a
  // domino's edge sliding down a turning neighbour: a held contact sinking in as an impact a
  // step). The separation, n·(p_b − p_a), is the same either way.
  // Two edges sliding along each other touch where the lines are closest, not at the material
  // points they touched at when the contact was found: those drift apart along the edges, and
  // the turn of the normal over that offset (n̈·(p_b − p_a)) would sink a held edge in.
  if (c.edge_edge) {
    const double cosine = f.ea.dot(f.eb), across = 1.0 - cosine * cosine;
    if (across > kEdgesCross * kEdgesCross) {
      const Vec3 r = f.pa - f.pb;
      const double da = f.ea.dot(r), db = f.eb.dot(r);
      const double sa = (cosine * db - da) / across, sb = (db - cosine * da) / across;
      const Vec3 qa = f.pa + sa * f.ea, qb = f.pb + sb * f.eb;
      // Lines near parallel are closest far along them (|r| / sin² of their angle: 1e5 m for
      // edges 0.06° apart that slid 0.1 m along each other). Points beyond either body are no
      // longer on its edge: those edges have slid off each other's ends, and the levers to
      // such points (a die's contact 10^5 m from its centre) would make its forces blow up.
      // The material points stay then; the separation along n is the same either way.
      const double slack = 1.0 + 1e-9;
      if ((qa - xa).norm() <= slack * A->bounding_radius() &&
          (qb - xb).norm() <= slack * B->bounding_radius()) {
        f.pa = qa;
        f.pb = qb;
        if (p.a.kind == Side::Member) f.ra = f.pa - xa;
        f.rb = f.pb - xb;
      }
    }
  }
  if (!(round_side(A) && round_side(B)) && c.normal_on >= 0 && !c.edge_edge) {
    if (c.normal_on == p.b.index) {
      f.pb = f.pa + f.n * f.n.dot(f.pb - f.pa);
      f.rb = f.pb - xb;
    } else if (p.a.kind == Side::Member && c.normal_on == p.a.index) {
      f.pa = f.pb + f.n * f.n.dot(f.pa - f.pb);
      f.ra = f.pa - xa;
    }
  }
  return f;
}

std::vector<IslandDynamics::Free> IslandDynamics::free_motion(const IslandState& s) const {
  std::vector<Free> k(s.size());
  for (std::size_t m = 0; m < s.size(); ++m) {
    const RigidBody& b = v_.member(static_cast<int>(m));
    Free& f = k[m];
    f.v = s[m].P * b.inverse_mass();
    f.F = b.mass() * v_.forces->gravity;
    if (v_.forces->linear_drag > 0.0) f.F -= v_.forces->linear_drag * f.v;
    f.tau.setZero();
    if (b.is_particle()) {
      f.R.setIdentity();
      f.Iinv.setZero();
      f.omega.setZero();
      f.alpha.setZero();
    } else {
      f.R = rotation_of(s[m], v_.rotation);
      f.Iinv = f.R * b.inverse_inertia_body().asDiagonal() * f.R.transpose();
      f.omega = f.Iinv * s[m].L;
      if (v_.forces->angular_drag > 0.0) f.tau -= v_.forces->angular_drag * f.omega;
      // α = I⁻¹ (τ − ω × L): the derivative of ω = I⁻¹ L with I⁻¹ rotating along.
      f.alpha = f.Iinv * (f.tau - f.omega.cross(s[m].L));
    }
    f.a = f.F * b.inverse_mass();
  }
  return k;
}

IslandDynamics::~IslandDynamics() = default;

IslandDynamics::HeldForces IslandDynamics::solve(const IslandState& s, const std::vector<Free>& k,
                                                 const Frames& f) const {
  const std::vector<IslandContact>& held = *held_;
  const int n = static_cast<int>(held.size());
  const std::vector<MassInfo> m = masses(v_, s);
  std::vector<char> local;
  std::vector<char>& active = active_ ? *active_ : local;
  // The held contacts' forces couple only through the bodies they share: the contact matrix is
  // block diagonal over the groups of contacts joined by members (the floor joins none), and
  // each group is a problem of its own. A landing heap of a hundred dice held 55 contacts in an
  // evaluation, the largest group 7: solved whole, the dense solves' work (the cube of the
  // rows) was 200 times the groups'.
  const std::vector<std::vector<int>> groups = contact_groups(v_, held);
  if (groups.size() <= 1) return solve_group(s, k, f, m, held, active, cache_);
  if (active.size() != static_cast<std::size_t>(n)) active.assign(static_cast<std::size_t>(n), 1);
  HeldForces out;
  out.normal = Eigen::VectorXd::Zero(n);
  out.friction.assign(static_cast<std::size_t>(n), Vec3::Zero());
  out.on_b.assign(static_cast<std::size_t>(n), Vec3::Zero());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::vector<int>& rows = groups[g];
    std::vector<IslandContact> part;
    Frames pf;
    std::vector<char> part_active;
    HeldRowsCache::GroupKey key;
    for (int i : rows) {
      const IslandContact& c = held[static_cast<std::size_t>(i)];
      key.emplace_back(c.pair, c.feature);
      part.push_back(held[static_cast<std::size_t>(i)]);
      pf.frame.push_back(f.frame[static_cast<std::size_t>(i)]);
      pf.a.push_back(f.a[static_cast<std::size_t>(i)]);
      pf.b.push_back(f.b[static_cast<std::size_t>(i)]);
      pf.round_pair.push_back(f.round_pair[static_cast<std::size_t>(i)]);
      part_active.push_back(active[static_cast<std::size_t>(i)]);
    }
    HeldRowsCache* part_cache = cache_ ? &cache_->group(key) : nullptr;
    const HeldForces r = solve_group(s, k, pf, m, part, part_active, part_cache);
    if (part_cache)
      cache_->iterative_residual =
          std::max(cache_->iterative_residual, part_cache->iterative_residual);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const auto i = static_cast<std::size_t>(rows[j]);
      out.normal(static_cast<Eigen::Index>(i)) = r.normal(static_cast<Eigen::Index>(j));
      out.friction[i] = r.friction[j];
      out.on_b[i] = r.on_b[j];
      if (part_active.size() == rows.size()) active[i] = part_active[j];
    }
  }
  return out;
}

IslandDynamics::HeldForces IslandDynamics::solve_group(
    const IslandState& s, const std::vector<Free>& k, const Frames& f,
    const std::vector<MassInfo>& m, const std::vector<IslandContact>& held,
    std::vector<char>& active, HeldRowsCache* cache) const {
  const int n = static_cast<int>(held.size());
  auto point_vel = [&](const SideGeometry& g, const Vec3& lever) -> Vec3 {
    if (g.member < 0) return Vec3::Zero();
    const Free& q = k[g.member];
    return q.v + q.omega.cross(lever);
  };
  // The force direction of each contact: the normal, and against the slip for a sliding one
  // (Coulomb kinetic friction proportional to the normal force: Baraff's dynamic friction,
  // which makes A unsymmetric).
  // How fast contact i's frame turns: a face's normal (and its tangents) with the face's body;
  // the normal of two edges, ±(e_a × e_b)/|e_a × e_b|, with both: ṅ from ė = ω × e on each
  // side, and the frame turns at n × ṅ (the least turn that carries n along). None: fixed.
  auto frame_turn = [&](int i) -> Vec3 {
    const IslandContact& c = held[static_cast<std::size_t>(i)];
    if (c.edge_edge) {
      const ContactFrame& fr = f.frame[i];
      const Vec3 wa = f.a[i].member >= 0 ? k[f.a[i].member].omega : Vec3(Vec3::Zero());
      const Vec3 wb = k[f.b[i].member].omega;
      const Vec3 u = fr.ea.cross(fr.eb);
      const double len = u.norm();
      if (len > kEdgesCross) {
        const Vec3 du = wa.cross(fr.ea).cross(fr.eb) + fr.ea.cross(wb.cross(fr.eb));
        const Vec3 ndot = c.edge_sign * (du - (u / len) * (u / len).dot(du)) / len;
        return fr.n.cross(ndot);
      }
    }
    return c.normal_on >= 0 ? k[c.normal_on].omega : Vec3(Vec3::Zero());
  };
  std::vector<Vec3> dir(static_cast<std::size_t>(n));
  Eigen::VectorXd b(n);
  std::vector<int> sticking;
  for (int i = 0; i < n; ++i) {
    const ContactFrame& c = f.frame[i];
    dir[i] = c.n;
    const IslandPair& p = v_.island->pairs[held[i].pair];
    const Vec3 dv = relative_velocity(v_, s, f, i);
    if (held[i].sliding && p.friction > 0.0) dir[i] -= p.friction * slip_unit(held[i], c, dv);
    if (!held[i].sliding && p.friction > 0.0) sticking.push_back(i);
    // Normal acceleration without contact forces: b = n·(a_pb − a_pa) + 2 ṅ·(v_pb − v_pa).
    auto point_acc = [&](const SideGeometry& g) -> Vec3 {
      if (g.member < 0) return Vec3::Zero();
      const Free& q = k[g.member];
      return q.a + q.alpha.cross(g.point_lever) + q.omega.cross(q.omega.cross(g.point_lever));
    };
    const Vec3 dvel = point_vel(f.b[i], f.b[i].point_lever) - point_vel(f.a[i], f.a[i].point_lever);
    double bi = c.n.dot(point_acc(f.b[i]) - point_acc(f.a[i]));
    if (f.round_pair[i]) {
      // Two round sides: the separation is |x_b − x_a| − r_a − r_b, whose second derivative
      // adds the speed across the line of centres squared over its length.
      const double L = (c.pb - c.pa).norm() + c.ra.norm() + c.rb.norm();
      const Vec3 across = dvel - c.n * c.n.dot(dvel);
      if (L > 0.0) bi += across.squaredNorm() / L;
    } else {
      const Vec3 ndot = frame_turn(i).cross(c.n);
      bi += 2.0 * ndot.dot(dvel);
      // A ball touches at its centre plus its radius along the normal, so where the normal turns
      // (a ball on a box's face as the box spins) the separation n·(x_ball − p) − r has
      // n̈·(x_ball − p) = −r |ṅ|² besides: a 0.5 m ball against a face turning at 4 rad/s is
      // pressed in at 8 m/s² more than the centre's acceleration says. Without it a struck
      // pyramid's ball, pushing a spinning box, was held with no force while it sank in, and
      // met the box again every 16 µs at 1e-4 m/s (149 impacts in 4 ms).
      bi -= (held[i].radius_a + held[i].radius_b) * ndot.squaredNorm();
    }
    b(i) = bi;
  }
  // The tangent rows of the sticking contacts: two unit tangents each, and the tangential
  // acceleration of the touching points without contact forces. A polyhedron's point is
  // material (a + α × r + ω × (ω × r)); a ball's is where it touches, not a material point, so
  // its slip changes by a + α × r alone (rolling has no slip to turn). A face's tangents turn
  // with it: (ω_face × t)·(v_pb − v_pa).
  std::vector<Vec3> t(2 * sticking.size());
  for (std::size_t j = 0; j < sticking.size(); ++j)
    tangents(f.frame[sticking[j]].n, t[2 * j], t[2 * j + 1]);
  Eigen::VectorXd bt(static_cast<Eigen::Index>(t.size()));
  for (int r = 0; r < bt.size(); ++r) {
    const int i = sticking[static_cast<std::size_t>(r / 2)];
    const Vec3& tr = t[static_cast<std::size_t>(r)];
    auto tangential_acc = [&](const SideGeometry& side, bool round) -> Vec3 {
      if (side.member < 0) return Vec3::Zero();
      const Free& q = k[side.member];
      Vec3 acc = q.a + q.alpha.cross(side.lever);
      if (!round) acc += q.omega.cross(q.omega.cross(side.lever));
      return acc;
    };
    const IslandPair& p = v_.island->pairs[held[i].pair];
    const bool round_a = round_side(v_.side_body(p.a)), round_b = round_side(v_.side_body(p.b));
    double bi = tr.dot(tangential_acc(f.b[i], round_b) - tangential_acc(f.a[i], round_a));
    if (held[i].normal_on >= 0 || held[i].edge_edge) {
      const Vec3 dvel = point_vel(f.b[i], f.b[i].lever) - point_vel(f.a[i], f.a[i].lever);
      bi += frame_turn(i).cross(tr).dot(dvel);
    }
    bt(r) = bi;
  }
  HeldForces out;
  // The forces along directions d (the normal, less friction where a contact slides); false
  // where no method reached an exact solution.
  const bool large = n + static_cast<int>(t.size()) > kSparseRows;
  bool slides = false;
  for (int i = 0; i < n; ++i) slides |= dir[i] != f.frame[i].n;
  auto solve_along = [&](const std::vector<Vec3>& d) -> bool {
    bool ok = true;
    // Where this problem has sliding friction in it and no method solves it, the caller solves
    // it again without that friction and discards this answer: no last resort for it (projected
    // Gauss–Seidel's 500 sweeps were a sixth of a struck pile's wall time).
    const bool retried = slides && &d == &dir;
    out.normal.resize(0);  // no answer yet
    out.friction.assign(static_cast<std::size_t>(n), Vec3::Zero());
    // A large island: its rows couple only where two contacts share a body, so the forces are
    // first sought by sparse block pivoting from the last clamped set (held_rows.hpp), which
    // most evaluations of a stretch keep; the dense solve below, whose work grows as the cube
    // of the rows, only where that does not settle.
    if (large) {
      HeldRows rows{&f, &m, &d, b, sticking, t, bt};
      Eigen::VectorXd fE;
      double residual = 0.0;
      const bool solved = solve_held_rows_sparse(rows, active, out.normal, fE, cache, &residual);
      if (cache && residual > 1e-9)
        cache->iterative_residual = std::max(cache->iterative_residual, residual);
      if (solved) {
        for (std::size_t j = 0; j < sticking.size(); ++j)
          out.friction[static_cast<std::size_t>(sticking[j])] =
              fE(2 * j) * t[2 * j] + fE(2 * j + 1) * t[2 * j + 1];
        return true;
      }
      // Beyond kSparseRows rows with friction in the matrix the dense pivots are no way out:
      // Lemke's method on a struck pyramid's 459 rows took minutes a solve. The caller takes
      // the reported fallback (below), down to a problem without friction.
      if (!sticking.empty()) return false;
      for (int i = 0; i < n; ++i)
        if (d[i] != f.frame[i].n) return false;
    }
    // A problem with friction that no solve reached at a nearby state of this step is not
    // tried again (HeldRowsCache::unsettled): Dantzig's and then Lemke's pivots on a struck
    // pile's 150 contacts cost seconds an evaluation before the fallback.
    std::vector<char> sliding_now(static_cast<std::size_t>(n), 0);
    for (int i = 0; i < n; ++i) sliding_now[static_cast<std::size_t>(i)] = d[i] != f.frame[i].n;
    const bool friction = !sticking.empty() ||
                          std::find(sliding_now.begin(), sliding_now.end(), 1) != sliding_now.end();
    if (friction && cache && cache->unsettled(sticking, sliding_now)) return false;
    const Eigen::MatrixXd A = contact_matrix(f, m, d);
    // With sliding friction A is not semidefinite, and the LCP may have several solutions: a box
    // sliding flat on its face is held by all four corners, or (as Dantzig's pivoting may find
    // from f = 0) by its two leading ones with the trailing ones accelerating away, a lift that
    // then rocks it on in micro-impacts. The contacts held are those that touch and do not
    // separate, so the first guess (where there is no last clamped set of this size) is all of
    // them clamped; it is kept when its forces are all >= 0 (a complementary solution).
    if (active.size() != static_cast<std::size_t>(b.size()))
      active.assign(static_cast<std::size_t>(b.size()), 1);
    if (sticking.empty()) {
      if (!solve_lcp_pivoting(A, b, out.normal, active, /*ridge_on_stall=*/false,
                              /*last_resort=*/!retried))
        ok = false;
    } else {
      // Static friction inside the stretch (Baraff 1994, section 7): a sticking contact that
      // presses keeps its slip, two tangential rows whose relative acceleration is zero, with
      // free (unbounded) forces; whether they stay in the cone is checked where a stretch
      // starts (hold_or_slip). The equalities are eliminated, f_E = −A_EE⁺ (A_EN f_N + b_E), and
      // the normal LCP is solved on the Schur complement: the tangent rows of coplanar points
      // (a face's four corners) are dependent, so A_EE is singular and b_E has round-off outside
      // its range, which a pivoting solve of the mixed problem does not survive; the
      // pseudo-inverse takes b_E in least squares and puts no force in A_EE's null space.
      // Which sticking contacts press is the normal LCP's own answer: begun from its last clamped
      // set, redone (at most 4 times) while they disagree.
      Frames g = f;
      std::vector<Vec3> gdir = d;
      for (std::size_t j = 0; j < sticking.size(); ++j) {
        const int i = sticking[j];
        for (int a = 0; a < 2; ++a) {
          g.frame.push_back(f.frame[i]);
          g.frame.back().n = t[2 * j + a];
          g.a.push_back(f.a[i]);
          g.b.push_back(f.b[i]);
          g.a.back().point_lever = f.a[i].lever;
          g.b.back().point_lever = f.b[i].lever;
          g.round_pair.push_back(f.round_pair[i]);
          gdir.push_back(t[2 * j + a]);
        }
      }
      const Eigen::MatrixXd M = contact_matrix(g, m, gdir);
      const int e = static_cast<int>(t.size());
      Eigen::VectorXd fE = Eigen::VectorXd::Zero(e);
      for (int round = 0; round < 4; ++round) {
        std::vector<int> rows;  // tangent rows (0-based in the tangent block) of pressing ones
        for (int r = 0; r < e; ++r)
          if (active[static_cast<std::size_t>(sticking[static_cast<std::size_t>(r / 2)])])
            rows.push_back(r);
        const std::vector<char> pressing = active;
        const int q = static_cast<int>(rows.size());
        Eigen::VectorXd y;
        Eigen::MatrixXd X;
        Eigen::MatrixXd S = A;
        Eigen::VectorXd c = b;
        Eigen::MatrixXd Ane(n, q);
        if (q > 0) {
          Eigen::MatrixXd Aee(q, q), Aen(q, n);
          Eigen::VectorXd be(q);
          for (int r = 0; r < q; ++r) {
            be(r) = bt(rows[r]);
            for (int cc = 0; cc < q; ++cc) Aee(r, cc) = M(n + rows[r], n + rows[cc]);
            Aen.row(r) = M.block(n + rows[r], 0, 1, n);
            Ane.col(r) = M.block(0, n + rows[r], n, 1);
          }
          Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
          cod.setThreshold(1e-10);
          cod.compute(Aee);
          X = cod.solve(Aen);
          y = cod.solve(be);
          S -= Ane * X;
          c -= Ane * y;
        }
        if (!solve_lcp_pivoting(S, c, out.normal, active, /*ridge_on_stall=*/false,
                                /*last_resort=*/!retried))
          ok = false;
        fE.setZero();
        if (q > 0) {
          const Eigen::VectorXd fq = -(X * out.normal + y);
          for (int r = 0; r < q; ++r) fE(rows[r]) = fq(r);
        }
        bool agree = true;
        for (int i : sticking)
          agree &= (active[static_cast<std::size_t>(i)] != 0) ==
                   (pressing[static_cast<std::size_t>(i)] != 0);
        if (agree) break;
      }
      for (std::size_t j = 0; j < sticking.size(); ++j)
        out.friction[static_cast<std::size_t>(sticking[j])] =
            fE(2 * j) * t[2 * j] + fE(2 * j + 1) * t[2 * j + 1];
    }
    if (!ok && friction && cache) cache->remember_unsettled(sticking, sliding_now);
    return ok;
  };
  std::vector<Vec3> along = dir;
  if (!solve_along(dir)) {
    if (failed_) *failed_ = true;
    // No solution reached with sliding friction in the matrix (Painlevé's paradox, or one the
    // pivots could not find): its last resort, projected Gauss–Seidel on an unsymmetric matrix,
    // can diverge (1e29 N on a pile of dice). The forces are then those of the same contacts
    // with no friction where they slide: a symmetric semidefinite problem, which always has a
    // solution and keeps every held contact from sinking in. μ times those normal forces
    // against the slip would not (dice sank 3 mm in a step, whose correction gained 0.2 J);
    // without them the sliding contacts do no work, and the stretch gains no energy.
    bool solved = false;
    if (slides) {
      for (int i = 0; i < n; ++i) along[i] = f.frame[i].n;
      solved = solve_along(along);
    }
    // A large island whose sticking contacts have no answer in their modes either (one pulls
    // when held and sinks when free: a struck box's corner) is solved without friction at all,
    // sparse, or at worst by the dense pivots on a symmetric semidefinite matrix.
    // So is an island whose last try was a problem remembered as unsettled (no answer).
    if (!solved && !sticking.empty() && (large || out.normal.size() != n)) {
      sticking.clear();
      t.clear();
      bt.resize(0);
      for (int i = 0; i < n; ++i) along[i] = f.frame[i].n;
      solve_along(along);
    }
  }
  out.on_b.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out.on_b[i] = out.normal(i) * along[i] + out.friction[i];
  return out;
}

Eigen::VectorXd IslandDynamics::contact_forces(const IslandState& s) const {
  if (!held_ || held_->empty()) return {};
  return solve(s, free_motion(s), frames_of(v_, *held_, s)).normal;
}

std::vector<Vec3> IslandDynamics::slip_accelerations(const IslandState& s) const {
  if (!held_ || held_->empty()) return {};
  std::vector<Free> k = free_motion(s);
  const Frames f = frames_of(v_, *held_, s);
  const HeldForces forces = solve(s, k, f);
  std::vector<Vec3> F(k.size(), Vec3::Zero()), tau(k.size(), Vec3::Zero());
  for (std::size_t i = 0; i < held_->size(); ++i) {
    if (f.b[i].member >= 0) {
      F[f.b[i].member] += forces.on_b[i];
      tau[f.b[i].member] += f.b[i].lever.cross(forces.on_b[i]);
    }
    if (f.a[i].member >= 0) {
      F[f.a[i].member] -= forces.on_b[i];
      tau[f.a[i].member] -= f.a[i].lever.cross(forces.on_b[i]);
    }
  }
  auto acc = [&](const SideGeometry& g) -> Vec3 {
    if (g.member < 0) return Vec3::Zero();
    const Free& q = k[g.member];
    const Vec3 a = q.a + F[g.member] * v_.member(g.member).inverse_mass();
    const Vec3 alpha = q.alpha + q.Iinv * tau[g.member];
    return a + alpha.cross(g.lever) + q.omega.cross(q.omega.cross(g.lever));
  };
  std::vector<Vec3> out(held_->size());
  for (std::size_t i = 0; i < held_->size(); ++i) {
    const Vec3 rel = acc(f.b[i]) - acc(f.a[i]);
    out[i] = rel - f.frame[i].n * f.frame[i].n.dot(rel);
  }
  return out;
}

IslandDynamics::HeldForces IslandDynamics::held_forces(const IslandState& s) const {
  if (!held_ || held_->empty()) return {};
  return solve(s, free_motion(s), frames_of(v_, *held_, s));
}

std::vector<Rate> IslandDynamics::operator()(const IslandState& s) const {
  if (evaluations_) *evaluations_ += static_cast<long>(s.size());
  std::vector<Free> k = free_motion(s);
  if (held_ && !held_->empty()) {
    const Frames f = frames_of(v_, *held_, s);
    const HeldForces forces = solve(s, k, f);
    for (std::size_t i = 0; i < held_->size(); ++i) {
      const Vec3& F = forces.on_b[i];
      if (f.b[i].member >= 0) {
        k[f.b[i].member].F += F;
        k[f.b[i].member].tau += f.b[i].lever.cross(F);
      }
      if (f.a[i].member >= 0) {
        k[f.a[i].member].F -= F;
        k[f.a[i].member].tau -= f.a[i].lever.cross(F);
      }
    }
  }
  std::vector<Rate> d(s.size());
  for (std::size_t m = 0; m < s.size(); ++m) {
    const RigidBody& b = v_.member(static_cast<int>(m));
    d[m].v = k[m].v;
    d[m].F = k[m].F;
    d[m].tau = k[m].tau;
    if (b.is_particle()) continue;
    if (v_.rotation == RotationRep::Quaternion) {
      // q̇ = ½ (0, ω) ⊗ q, written out in (w, x, y, z) order.
      const Vec3 qv = s[m].q.vec();
      const double qw = s[m].q.w();
      d[m].qdot(0) = -0.5 * k[m].omega.dot(qv);
      d[m].qdot.tail<3>() = 0.5 * (qw * k[m].omega + k[m].omega.cross(qv));
    } else {
      d[m].Rdot = star(k[m].omega) * s[m].R;
    }
  }
  return d;
}

namespace {

// An island as an integration system (integrator_schemes.hpp): every member advanced as a
// single body is, the error the largest of the members'.
struct IslandSystem {
  using State = IslandState;
  using Rates = std::vector<Rate>;
  struct BodyError {
    Vec3 dx = Vec3::Zero(), dP = Vec3::Zero(), dL = Vec3::Zero();
    Vec4 dq = Vec4::Zero();
    Mat3 dR = Mat3::Zero();
  };
  using ErrorSum = std::vector<BodyError>;
  const IslandDynamics& f;
  const std::vector<Stepping>& per_body;

  bool particle(std::size_t m) const { return f.view().member(static_cast<int>(m)).is_particle(); }
  RotationRep rep() const { return f.view().rotation; }
  Rates eval(const State& s) const { return f(s); }
  // Each field moves by its own rate: a kick (momenta) then a drift (poses) is the full step.
  State add(const State& s, const Rates& d, double h) const { return drift(kick(s, d, h), d, h); }
  State kick(const State& s, const Rates& d, double h) const {
    State out = s;
    for (std::size_t m = 0; m < s.size(); ++m) {
      out[m].P += h * d[m].F;
      if (!particle(m)) out[m].L += h * d[m].tau;
    }
    return out;
  }
  State drift(const State& s, const Rates& d, double h) const {
    State out = s;
    for (std::size_t m = 0; m < s.size(); ++m) {
      out[m].x += h * d[m].v;
      if (particle(m)) continue;
      if (rep() == RotationRep::Quaternion) {
        out[m].q.w() += h * d[m].qdot(0);
        out[m].q.vec() += h * d[m].qdot.tail<3>();
      } else {
        out[m].R += h * d[m].Rdot;
      }
    }
    return out;
  }
  ErrorSum error_sum() const { return ErrorSum(per_body.size()); }
  void accumulate_error(ErrorSum& e, const Rates& k, double w) const {
    for (std::size_t m = 0; m < e.size(); ++m) {
      e[m].dx += w * k[m].v;
      e[m].dP += w * k[m].F;
      if (particle(m)) continue;
      e[m].dL += w * k[m].tau;
      if (rep() == RotationRep::Quaternion)
        e[m].dq += w * k[m].qdot;
      else
        e[m].dR += w * k[m].Rdot;
    }
  }
  double scaled_error(const State& s, const ErrorSum& e, const Stepping&) const {
    double worst = 0.0;
    for (std::size_t m = 0; m < e.size(); ++m)
      worst = std::max(worst,
                       body_scaled_error(f.view().member(static_cast<int>(m)), rep(), s[m], e[m].dx,
                                         e[m].dP, e[m].dL, e[m].dq, e[m].dR, per_body[m]));
    return worst;
  }
  void finish(State& s, StepInfo& info) const {
    for (std::size_t m = 0; m < s.size(); ++m) {
      if (particle(m)) continue;
      info.orientation_drift = std::max(info.orientation_drift, orientation_drift(s[m], rep()));
      normalize_orientation(s[m], rep());
    }
  }
};

}  // namespace

IslandState integrate_island(const IslandDynamics& f, const IslandState& s, double h,
                             const Stepping& how, const std::vector<Stepping>& per_body,
                             StepInfo* info) {
  return schemes::step(IslandSystem{f, per_body}, s, h, how, info);
}

double normal_speed(const IslandView& v, const IslandContact& c, const IslandState& s) {
  const std::vector<IslandContact> one{c};
  const Frames f = frames_of(v, one, s);
  return f.frame[0].n.dot(relative_velocity(v, s, f, 0));
}

double island_kinetic_energy(const IslandView& v, const IslandState& s) {
  double e = 0.0;
  for (std::size_t m = 0; m < s.size(); ++m) {
    const RigidBody& b = v.member(static_cast<int>(m));
    e += 0.5 * s[m].P.squaredNorm() * b.inverse_mass();
    if (b.is_particle()) continue;
    const Mat3 R = rotation_of(s[m], v.rotation);
    const Vec3 omega = R * b.inverse_inertia_body().asDiagonal() * R.transpose() * s[m].L;
    e += 0.5 * omega.dot(s[m].L);
  }
  return e;
}

namespace {

// The normal rows of `contacts` at s: their frames, the matrix from normal impulses to normal
// speeds, and the normal speeds now.
struct NormalRows {
  Frames f;
  Eigen::MatrixXd A;
  Eigen::VectorXd vn;
};

NormalRows normal_rows(const IslandView& v, const std::vector<IslandContact>& contacts,
                       const IslandState& s) {
  const int n = static_cast<int>(contacts.size());
  NormalRows rows;
  rows.f = frames_of(v, contacts, s);
  const std::vector<MassInfo> m = masses(v, s);
  std::vector<Vec3> normals(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) normals[i] = rows.f.frame[i].n;
  rows.A = contact_matrix(rows.f, m, normals);
  rows.vn.resize(n);
  for (int i = 0; i < n; ++i)
    rows.vn(i) = rows.f.frame[i].n.dot(relative_velocity(v, s, rows.f, i));
  return rows;
}

// The impulses along the normals, least squares with minimum norm over dependent points, that
// bring the normal speed of each of `points` (not empty) to zero: a projection in the kinetic
// metric, so it never gains energy.
void stop_points(const Eigen::MatrixXd& A, const Frames& f, const std::vector<int>& points,
                 const std::vector<int>& group, const Eigen::VectorXd& vn, IslandState& s,
                 std::vector<double>& impulses) {
  const int q = static_cast<int>(points.size());
  Eigen::MatrixXd Ap(q, q);
  Eigen::VectorXd rhs(q);
  std::vector<int> point_group(static_cast<std::size_t>(q));
  for (int r = 0; r < q; ++r) {
    point_group[static_cast<std::size_t>(r)] = group[static_cast<std::size_t>(points[r])];
    rhs(r) = -vn(points[r]);
    for (int c = 0; c < q; ++c) Ap(r, c) = A(points[r], points[c]);
  }
  // Exactly, the projection's energy change is −½ vnᵀ A⁺ vn <= 0. Many dependent points (a
  // struck pile: 78 contacts) make A numerically near-singular, and its round-off directions,
  // inverted, gained 0.35 J: an answer whose energy change j·vn + ½ jᵀAj is positive is not
  // applied (the passes go on without it).
  const Eigen::VectorXd j = block_least_norm(Ap, rhs, point_group);
  const double work = -rhs.dot(j);
  if (work + 0.5 * j.dot(Ap * j) > 1e-12 * std::abs(work)) return;
  for (int r = 0; r < q; ++r) {
    impulses[points[r]] += j(r);
    apply(s, f, points[r], j(r) * f.frame[points[r]].n);
  }
}

}  // namespace

double resolve_island_impacts(const IslandView& v, const std::vector<IslandContact>& contacts,
                              IslandState& s, double rest_speed, bool inelastic,
                              std::vector<double>& impulses) {
  const int n = static_cast<int>(contacts.size());
  impulses.assign(static_cast<std::size_t>(n), 0.0);
  if (n == 0) return 0.0;
  const double e_start = island_kinetic_energy(v, s);
  // Impulses change momenta, not poses: the frames and the matrix hold for every pass.
  const Frames f = frames_of(v, contacts, s);
  const std::vector<MassInfo> m = masses(v, s);
  std::vector<Vec3> normals(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) normals[i] = f.frame[i].n;
  const Eigen::MatrixXd A = contact_matrix(f, m, normals);
  const std::vector<int> group = row_groups(v, contacts, 1);  // each contact's block of A
  auto speeds = [&] {
    Eigen::VectorXd vn(n);
    for (int i = 0; i < n; ++i) vn(i) = f.frame[i].n.dot(relative_velocity(v, s, f, i));
    return vn;
  };
  Eigen::VectorXd vn = speeds();
  const double fastest = std::max(0.0, -vn.minCoeff());
  // Approach slower than 1e-9 of the impact's is round-off of an exchange already made, and
  // under gravity one slower than 1e-12 sqrt(g l) (l: the smallest member's reach; 1e-6 of the
  // speed below which contacts are held) is round-off of a resting contact: 4e-29 m/s after a
  // friction impulse, whose LCP (|b| at round-off, a rank-deficient A) only stalls pivoting.
  double smallest = INFINITY;
  for (std::size_t k = 0; k < s.size(); ++k)
    smallest = std::min(smallest, v.member(static_cast<int>(k)).bounding_radius());
  const double eps =
      std::max(1e-9 * fastest, 1e-12 * std::sqrt(v.forces->gravity.norm() * smallest));
  if (fastest <= eps) return 0.0;
  // Only the pairs that approach take part in a pass (all their touching points together, as
  // a face lands on the floor at once), and passes repeat until none does: an impact then
  // travels along a chain of touching bodies (Newton's cradle) instead of being shared out at
  // once by pairs that were not approaching.
  const int max_passes = 4 * n + 16;
  std::vector<int> plastic_last;  // the points the last Zeno pass stopped
  std::vector<char> stopped(v.island->pairs.size(), 0);  // pairs kept in the Zeno passes
  for (int pass = 0; pass < max_passes; ++pass) {
    std::vector<char> approaching_pair(v.island->pairs.size(), 0);
    for (int i = 0; i < n; ++i)
      if (vn(i) < -eps) approaching_pair[contacts[i].pair] = 1;
    std::vector<int> set;
    for (int i = 0; i < n; ++i)
      if (approaching_pair[contacts[i].pair]) set.push_back(i);
    if (set.empty()) break;
    const int k = static_cast<int>(set.size());
    Eigen::MatrixXd As(k, k);
    for (int r = 0; r < k; ++r)
      for (int c = 0; c < k; ++c) As(r, c) = A(set[r], set[c]);
    const double e_before = island_kinetic_energy(v, s);
    const IslandState before = s;
    auto solve = [&](bool elastic) {
      Eigen::VectorXd rhs(k);
      for (int r = 0; r < k; ++r) {
        const int i = set[r];
        const double e = v.island->pairs[contacts[i].pair].restitution;
        const bool bounces = elastic && vn(i) < -rest_speed;
        rhs(r) = bounces ? (1.0 + e) * vn(i) : vn(i);
      }
      Eigen::VectorXd j;
      std::vector<char> active;
      if (elastic)
        solve_lcp_pivoting(As, rhs, j, active, /*ridge_on_stall=*/true);
      else
        solve_lcp_dissipative(As, rhs, j, active);
      for (int r = 0; r < k; ++r) {
        impulses[set[r]] += j(r);
        apply(s, f, set[r], j(r) * f.frame[set[r]].n);
      }
      return j;
    };
    double approach = 0.0;
    for (int i : set) approach = std::max(approach, -vn(i));
    // A large island (a struck pile: 463 contacts) in the Zeno limit: the projections below,
    // pair by pair, each leave others approaching (a struck 10-row pyramid: ~3 000 passes of
    // 150–280 points for one stretch's end, 40–60 % of its step). After 16 passes the rest is
    // the island's inelastic impact at once (after the loop: one LCP over all its contacts,
    // solved iteratively above kLargeLcpRows rows, which never gains energy). At once from the
    // first pass was tried: the struck pyramid's strike step then did not finish in 190 s.
    if (approach <= rest_speed && n > kLargeLcpRows && pass >= 16) break;
    if (approach <= rest_speed) {
      // Slower than the rest speed: the Zeno limit. A box rocking on a face (a sliding one
      // is rocked by its friction torque) meets it edge after edge in ever shorter, ever
      // slower inelastic impacts, each lifting the other edge (Housner's rocking block); their
      // sum leaves every touching point of the pair at rest along the normal. That end state
      // at once: the impulses that zero the normal speed of every touching point of the
      // approaching pairs that is not leaving faster than the rest speed, least squares
      // (minimum norm) over dependent points. It is a projection in the kinetic metric, so it
      // never gains energy.
      // The same holds across pairs: a domino wedged between the floor and the next one,
      // stopped at one, lifts off the other and falls back, in impacts that never end. So the
      // touching points of every pair that shares a body with an approaching one take part.
      // From the 16th pass on, so do the pairs that a pass since then stopped (their points
      // still slower than the rest speed). Pass after pass these projections, onto
      // {v : the normal speeds of a set are zero}, alternate, and alternating projections
      // converge only linearly to the projection onto their sets' intersection (von Neumann):
      // the one projection onto their union. Each pass stopping only its own set, a struck
      // pyramid of 6 rows ran 105 resolutions to the pass cap (4 n + 16, ~550 passes of
      // 100–150 points each: 24 s of a 36 s run), and 220 of the twenty dominoes' resolutions
      // took 17–311 passes. Not from the first pass: the dominoes then went out of their plane
      // (3e-9 m at a sample, where the limit is 1e-9 m; after the 16th they stay within 5e-11).
      std::vector<char> body_hit(s.size(), 0);
      for (int i : set) {
        const IslandPair& p = v.island->pairs[contacts[i].pair];
        body_hit[static_cast<std::size_t>(p.b.index)] = 1;
        if (p.a.kind == Side::Member) body_hit[static_cast<std::size_t>(p.a.index)] = 1;
      }
      std::vector<int> plastic;
      for (int i = 0; i < n; ++i) {
        const IslandPair& p = v.island->pairs[contacts[i].pair];
        const bool joined =
            body_hit[static_cast<std::size_t>(p.b.index)] ||
            (p.a.kind == Side::Member && body_hit[static_cast<std::size_t>(p.a.index)]);
        if ((joined || stopped[static_cast<std::size_t>(contacts[i].pair)]) && vn(i) <= rest_speed)
          plastic.push_back(i);
      }
      if (pass >= 16)
        for (int i : plastic) stopped[static_cast<std::size_t>(contacts[i].pair)] = 1;
      stop_points(A, f, plastic, group, vn, s, impulses);
      vn = speeds();
      plastic_last = plastic;
      continue;
    }
    const std::vector<double> saved = impulses;
    solve(!inelastic);
    // Simultaneous Newton restitution can return more energy than came in; the inelastic
    // solution is a projection in the kinetic metric and never does.
    if (island_kinetic_energy(v, s) > e_before * (1.0 + 1e-12) + 1e-300) {
      s = before;
      impulses = saved;
      solve(false);
    }
    vn = speeds();
  }
  // Passes that do not end: a light body between a heavy one and the floor trades impulses with
  // both ~ sqrt(M/m) times (the billiard-ball count), 10^3 passes at 1000:1. After the pass cap
  // the rest is resolved at once, as Poisson's law over every contact: the inelastic LCP's
  // compression impulse J (after it no contact approaches), then e J again with the smallest
  // restitution e among them. Its energy change is -(1 - e²)/2 · JᵀAJ <= 0 (J's
  // complementarity gives J·v = -JᵀAJ), so it never gains energy; a last inelastic projection
  // stops any contact that the restitution impulse turned into an approach.
  if (vn.minCoeff() < -eps) {
    Eigen::VectorXd j;
    std::vector<char> active;
    solve_lcp_dissipative(A, vn, j, active, true);
    double e = inelastic ? 0.0 : 1.0;
    for (int i = 0; i < n; ++i)
      if (j(i) > 0.0 && vn(i) < -rest_speed)
        e = std::min(e, v.island->pairs[contacts[i].pair].restitution);
      else if (j(i) > 0.0)
        e = 0.0;
    for (int i = 0; i < n; ++i) {
      impulses[i] += (1.0 + e) * j(i);
      apply(s, f, i, (1.0 + e) * j(i) * f.frame[i].n);
    }
    vn = speeds();
    if (vn.minCoeff() < -eps) {
      solve_lcp_dissipative(A, vn, j, active, true);
      for (int i = 0; i < n; ++i) {
        impulses[i] += j(i);
        apply(s, f, i, j(i) * f.frame[i].n);
      }
    }
  }
  bool friction = false;
  for (int i = 0; i < n; ++i) friction |= v.island->pairs[contacts[i].pair].friction > 0.0;
  if (friction) {
    // A slip slower than 1e-9 sqrt(g l) is round-off of a contact held sticking (its
    // direction is noise): no kinetic impulse along it.
    apply_island_friction(v, contacts, impulses, s,
                          1e-9 * std::sqrt(v.forces->gravity.norm() * smallest));
    // A tangential impulse can turn a body so that a point approaches again: a last
    // inelastic pass stops every approach (a projection: it only dissipates).
    vn = speeds();
    // After a Zeno pass the friction impulse turns the body it stopped (a sliding box rocked by
    // its friction torque) and lifts some of its points as slowly as it lowers others: stopped
    // again together, in the same projection, or they rock on in impacts microseconds apart.
    std::vector<int> again;
    for (int i : plastic_last)
      if (std::abs(vn(i)) <= rest_speed) again.push_back(i);
    if (!again.empty()) {
      stop_points(A, f, again, group, vn, s, impulses);
      vn = speeds();
    }
    std::vector<char> approaching_pair(v.island->pairs.size(), 0);
    for (int i = 0; i < n; ++i)
      if (vn(i) < -eps) approaching_pair[contacts[i].pair] = 1;
    std::vector<int> set;
    for (int i = 0; i < n; ++i)
      if (approaching_pair[contacts[i].pair]) set.push_back(i);
    if (!set.empty()) {
      const int k = static_cast<int>(set.size());
      Eigen::MatrixXd As(k, k);
      Eigen::VectorXd rhs(k);
      for (int r = 0; r < k; ++r) {
        rhs(r) = vn(set[r]);
        for (int c = 0; c < k; ++c) As(r, c) = A(set[r], set[c]);
      }
      Eigen::VectorXd j;
      std::vector<char> active;
      solve_lcp_dissipative(As, rhs, j, active);
      for (int r = 0; r < k; ++r) {
        impulses[set[r]] += j(r);
        apply(s, f, set[r], j(r) * f.frame[set[r]].n);
      }
    }
  }
  return island_kinetic_energy(v, s) - e_start;
}

void stop_island_points(const IslandView& v, const std::vector<IslandContact>& contacts,
                        IslandState& s) {
  const int n = static_cast<int>(contacts.size());
  if (n == 0) return;
  const NormalRows rows = normal_rows(v, contacts, s);
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  std::vector<double> impulses(static_cast<std::size_t>(n), 0.0);
  stop_points(rows.A, rows.f, all, row_groups(v, contacts, 1), rows.vn, s, impulses);
}

bool apply_island_friction(const IslandView& v, const std::vector<IslandContact>& contacts,
                           const std::vector<double>& normal_impulse, IslandState& s,
                           double still) {
  const int n = static_cast<int>(contacts.size());
  if (n == 0) return true;
  const Frames f = frames_of(v, contacts, s);
  const std::vector<MassInfo> m = masses(v, s);
  std::vector<Vec3> t(static_cast<std::size_t>(2 * n));
  std::vector<double> mu(static_cast<std::size_t>(n));
  Eigen::VectorXd u(2 * n);
  for (int i = 0; i < n; ++i) {
    tangents(f.frame[i].n, t[2 * i], t[2 * i + 1]);
    mu[i] = v.island->pairs[contacts[i].pair].friction;
    const Vec3 dv = relative_velocity(v, s, f, i);
    u(2 * i) = mu[i] > 0.0 ? dv.dot(t[2 * i]) : 0.0;
    u(2 * i + 1) = mu[i] > 0.0 ? dv.dot(t[2 * i + 1]) : 0.0;
  }
  if (u.cwiseAbs().maxCoeff() == 0.0) return true;
  bool solvable = false;  // the joint sticking impulse exists (it may still leave the cones)
  // Sticking, jointly with the normal rows of the contacts that press: a tangential impulse at
  // a box's base also turns it (a unit impulse at its four corners changes their slip 2.5
  // times as much as the centre's velocity), which the pressing contacts do not allow: their
  // normal impulses change with it so that their normal speeds stay as they are. Rows per
  // contact: its normal, then its two tangents; least squares, minimum norm (dependent
  // points), a projection in the kinetic metric, so it never gains energy.
  {
    Frames f3;
    std::vector<Vec3> dir;
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        f3.frame.push_back(f.frame[i]);
        f3.a.push_back(f.a[i]);
        f3.b.push_back(f.b[i]);
        if (a > 0) {
          f3.frame.back().n = t[2 * i + a - 1];
          f3.a.back().point_lever = f.a[i].lever;
          f3.b.back().point_lever = f.b[i].lever;
        }
        dir.push_back(f3.frame.back().n);
      }
    Eigen::MatrixXd M = contact_matrix(f3, m, dir);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * n);
    for (int i = 0; i < n; ++i) {
      rhs(3 * i + 1) = -u(2 * i);
      rhs(3 * i + 2) = -u(2 * i + 1);
      for (int a = 0; a < 3; ++a) {
        const bool unused = a == 0 ? !(normal_impulse[i] > 0.0) : mu[i] == 0.0;
        if (!unused) continue;
        const int r = 3 * i + a;
        M.row(r).setZero();
        M.col(r).setZero();
        M(r, r) = 1.0;
        rhs(r) = 0.0;
      }
    }
    const Eigen::VectorXd x = block_least_norm(M, rhs, row_groups(v, contacts, 3));
    solvable = (M * x - rhs).norm() <= 1e-9 * std::max(rhs.norm(), 1e-300);
    bool inside = solvable;
    for (int i = 0; i < n && inside; ++i) {
      const double normal = normal_impulse[i] + x(3 * i);
      inside = normal >= 0.0 && x.segment<2>(3 * i + 1).norm() <= mu[i] * normal * (1.0 + 1e-9);
    }
    if (inside) {
      for (int i = 0; i < n; ++i)
        apply(s, f, i,
              x(3 * i) * f.frame[i].n + x(3 * i + 1) * t[2 * i] + x(3 * i + 2) * t[2 * i + 1]);
      return true;
    }
  }
  // K maps tangential impulses to changes of the tangential slips (rows: tangents of every
  // contact; the frictionless ones have rows and columns too, with zero impulse).
  Frames f2 = f;
  f2.frame.resize(static_cast<std::size_t>(2 * n));
  f2.a.resize(static_cast<std::size_t>(2 * n));
  f2.b.resize(static_cast<std::size_t>(2 * n));
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 2; ++a) {
      f2.frame[2 * i + a] = f.frame[i];
      f2.frame[2 * i + a].n = t[2 * i + a];
      f2.a[2 * i + a] = f.a[i];
      f2.b[2 * i + a] = f.b[i];
      // The slip is of the surface points: the force lever, also for round sides.
      f2.a[2 * i + a].point_lever = f.a[i].lever;
      f2.b[2 * i + a].point_lever = f.b[i].lever;
    }
  Eigen::MatrixXd K = contact_matrix(f2, m, t);
  for (int i = 0; i < n; ++i)
    if (mu[i] == 0.0)
      for (int a = 0; a < 2; ++a) {
        K.row(2 * i + a).setZero();
        K.col(2 * i + a).setZero();
        K(2 * i + a, 2 * i + a) = 1.0;
      }
  Eigen::VectorXd imp = -block_least_norm(K, u, row_groups(v, contacts, 2));
  // Where the joint impulse exists, it left a cone (above): the contacts slide. Otherwise (no
  // pressing contact to turn against) the tangential impulses alone decide.
  bool sticks = !solvable;
  for (int i = 0; i < n; ++i)
    if (imp.segment<2>(2 * i).norm() > mu[i] * normal_impulse[i] * (1.0 + 1e-9)) sticks = false;
  if (!sticks) {
    for (int i = 0; i < n; ++i) {
      const double slip = u.segment<2>(2 * i).norm();
      imp.segment<2>(2 * i) =
          slip > still ? Eigen::Vector2d(-mu[i] * normal_impulse[i] * u.segment<2>(2 * i) / slip)
                       : Eigen::Vector2d::Zero();
    }
    // Kinetic energy along σ·imp is KE0 + σ (u·imp) + ½ σ² impᵀK imp: the σ in [0, 1] that
    // dissipates most, so sliding friction stops a slip but never reverses it.
    const double slope = u.dot(imp), curvature = imp.dot(K * imp);
    if (slope >= 0.0) return false;
    imp *= curvature > 0.0 ? std::min(1.0, -slope / curvature) : 1.0;
  }
  for (int i = 0; i < n; ++i) apply(s, f, i, imp(2 * i) * t[2 * i] + imp(2 * i + 1) * t[2 * i + 1]);
  return sticks;
}

void restore_normal_speeds(const IslandView& v, const std::vector<IslandContact>& held,
                           const std::vector<double>& normal_impulse, IslandState& s) {
  const int n = static_cast<int>(held.size());
  if (n == 0) return;
  const NormalRows rows = normal_rows(v, held, s);
  const Frames& f = rows.f;
  const Eigen::MatrixXd& A = rows.A;
  const Eigen::VectorXd& vn = rows.vn;
  const Eigen::VectorXd d = block_least_norm(A, -vn, row_groups(v, held, 1));
  bool feasible = (A * d + vn).norm() <= 1e-9 * std::max(vn.norm(), 1e-300);
  for (int i = 0; i < n && feasible; ++i)
    feasible = normal_impulse[i] + d(i) >= -1e-12 * std::max(normal_impulse[i], 1e-300);
  if (feasible) {
    for (int i = 0; i < n; ++i) apply(s, f, i, d(i) * f.frame[i].n);
    return;
  }
  std::vector<double> unused;
  resolve_island_impacts(v, held, s, INFINITY, true, unused);
}

namespace {

// The equilibrium rows of an island: for every member its force and torque balance, J β = −W,
// where column c of J is the wrench of a unit force along dir[c] at contact owner[c] (on b, and
// its opposite on a) and W the members' weights.
struct Balance {
  Eigen::SparseMatrix<double> J;
  Eigen::VectorXd W;
};
Balance balance_rows(const IslandView& v, const Frames& f, const std::vector<Vec3>& dir,
                     const std::vector<int>& owner) {
  const int members = static_cast<int>(v.island->members.size());
  Balance out;
  out.W = Eigen::VectorXd::Zero(6 * members);
  for (int k = 0; k < members; ++k) out.W.segment<3>(6 * k) = v.member(k).mass() * v.forces->gravity;
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t c = 0; c < dir.size(); ++c) {
    const int i = owner[c];
    for (int side = 0; side < 2; ++side) {
      const SideGeometry& g = side == 0 ? f.a[i] : f.b[i];
      if (g.member < 0) continue;
      const double sign = side == 0 ? -1.0 : 1.0;
      const Vec3 torque = g.lever.cross(dir[c]);
      for (int r = 0; r < 3; ++r) {
        entries.emplace_back(6 * g.member + r, static_cast<int>(c), sign * dir[c](r));
        if (!v.member(g.member).is_particle())
          entries.emplace_back(6 * g.member + 3 + r, static_cast<int>(c), sign * torque(r));
      }
    }
  }
  out.J.resize(6 * members, static_cast<Eigen::Index>(dir.size()));
  out.J.setFromTriplets(entries.begin(), entries.end());  // duplicates (a == b) are summed
  return out;
}

// The least-norm forces β = Jᵀ y, (J Jᵀ) y = −W, over each contact's normal (`with_friction`
// false) or its normal and two tangents. Least-norm forces pull as well as push (two boxes side
// by side trade a couple that unloads their supports), so a contact whose normal force comes
// out negative is left out and the rest solved again, a few rounds (an active-set search that
// only ever drops). The answer is then pulled into the cones (a normal of round-off size below
// zero to zero, a tangential part to the pyramid's inscribed circle, mu cos 22.5° times the
// normal, so that it is one the pyramid test below also accepts): balanced when the residual
// is round-off. Sparse (each column touches two members), so an island of hundreds of resting
// bodies costs a few sparse factorisations instead of an active-set search over thousands of
// dense columns.
bool least_norm_balances(const IslandView& v, const Frames& f, const std::vector<double>& mu,
                         bool with_friction) {
  const int n = static_cast<int>(f.frame.size());
  std::vector<Vec3> dir;
  std::vector<int> owner;
  for (int i = 0; i < n; ++i) {
    dir.push_back(f.frame[i].n), owner.push_back(i);
    if (!with_friction || mu[i] <= 0.0) continue;
    Vec3 t1, t2;
    tangents(f.frame[i].n, t1, t2);
    dir.push_back(t1), owner.push_back(i);
    dir.push_back(t2), owner.push_back(i);
  }
  const Balance rows = balance_rows(v, f, dir, owner);
  const int u = static_cast<int>(dir.size());
  Eigen::VectorXd keep = Eigen::VectorXd::Ones(u);  // 0: the column's contact is left out
  Eigen::VectorXd beta;
  for (int round = 0; round < 6; ++round) {
    const Eigen::SparseMatrix<double> Jk = rows.J * keep.asDiagonal();
    Eigen::SparseMatrix<double> JJt = Jk * Jk.transpose();
    double diag = 0.0;
    for (int k = 0; k < JJt.rows(); ++k) diag = std::max(diag, JJt.coeff(k, k));
    // A direction no contact can push (a frictionless box's spin about the normal) is
    // singular: a ridge of round-off size keeps the factorisation going; the residual judges.
    for (int k = 0; k < JJt.rows(); ++k) JJt.coeffRef(k, k) += 1e-13 * diag;
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(JJt);
    if (ldlt.info() != Eigen::Success) return false;
    beta = Jk.transpose() * ldlt.solve(-rows.W);
    const double small = 1e-9 * beta.cwiseAbs().maxCoeff();
    bool dropped = false;
    for (int c = 0; c < u; ++c)
      if (dir[c] == f.frame[owner[c]].n && beta(c) < -small)
        for (int d = c; d < u && owner[d] == owner[c]; ++d) keep(d) = 0.0, dropped = true;
    if (!dropped) break;
  }
  for (int c = 0; c < u;) {
    const int i = owner[c];
    const int width = with_friction && mu[i] > 0.0 ? 3 : 1;
    const double normal = std::max(beta(c), 0.0);
    beta(c) = normal;
    if (width == 3) {
      const double slip = beta.segment<2>(c + 1).norm(), cap = mu[i] * std::cos(kPi / 8.0) * normal;
      if (slip > cap) beta.segment<2>(c + 1) *= cap / slip;
    }
    c += width;
  }
  return (rows.J * beta + rows.W).norm() <= 1e-9 * rows.W.norm();
}

}  // namespace

bool island_in_equilibrium(const IslandView& v, const std::vector<IslandContact>& contacts,
                           const IslandState& s) {
  const int n = static_cast<int>(contacts.size());
  if (n == 0) return false;
  const Frames f = frames_of(v, contacts, s);
  std::vector<double> mu(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) mu[i] = v.island->pairs[contacts[i].pair].friction;
  // The quick sufficient tests first: the least-norm normal forces (a stack, a pyramid), then
  // with friction (a box on a ramp). Where both leave a residual, the exact search decides.
  if (least_norm_balances(v, f, mu, false) || least_norm_balances(v, f, mu, true)) return true;
  // Each contact force as a non-negative combination of directions: the normal alone, or with
  // friction the 8 edges n + mu (cos k45° t1 + sin k45° t2) of the pyramid inscribed in its
  // cone (it holds all but 8 % of the cone, cos 22.5°): conservative, never a force outside.
  std::vector<Vec3> dir;
  std::vector<int> owner;
  for (int i = 0; i < n; ++i) {
    if (mu[i] <= 0.0) {
      dir.push_back(f.frame[i].n), owner.push_back(i);
      continue;
    }
    Vec3 t1, t2;
    tangents(f.frame[i].n, t1, t2);
    for (int k = 0; k < 8; ++k) {
      const double a = k * (kPi / 4.0);
      dir.push_back(f.frame[i].n + mu[i] * (std::cos(a) * t1 + std::sin(a) * t2));
      owner.push_back(i);
    }
  }
  const int u = static_cast<int>(dir.size());
  const Balance rows = balance_rows(v, f, dir, owner);
  const Eigen::MatrixXd J(rows.J);
  const Eigen::VectorXd& W = rows.W;
  // Non-negative least squares (Lawson & Hanson, "Solving Least Squares Problems", ch. 23):
  // β >= 0 minimising |J β + W|. Balanced when the residual is round-off (1e-9 of the weights).
  const Eigen::VectorXd b = -W;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(u);
  std::vector<char> in_p(static_cast<std::size_t>(u), 0);
  const double tol = 1e-12 * std::max(J.cwiseAbs().maxCoeff(), 1e-300) * W.norm();
  for (int outer = 0; outer < 3 * u + 10; ++outer) {
    const Eigen::VectorXd w = J.transpose() * (b - J * x);
    int j = -1;
    for (int c = 0; c < u; ++c)
      if (!in_p[c] && w(c) > tol && (j < 0 || w(c) > w(j))) j = c;
    if (j < 0) break;
    in_p[j] = 1;
    for (int inner = 0; inner < 3 * u + 10; ++inner) {
      std::vector<int> set;
      for (int c = 0; c < u; ++c)
        if (in_p[c]) set.push_back(c);
      Eigen::MatrixXd Jp(J.rows(), static_cast<Eigen::Index>(set.size()));
      for (std::size_t k = 0; k < set.size(); ++k)
        Jp.col(static_cast<Eigen::Index>(k)) = J.col(set[k]);
      const Eigen::VectorXd zp =
          Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Jp).solve(b);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(u);
      for (std::size_t k = 0; k < set.size(); ++k) z(set[k]) = zp(static_cast<Eigen::Index>(k));
      bool positive = true;
      for (int c : set) positive &= z(c) > 0.0;
      if (positive) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (int c : set)
        if (z(c) <= 0.0) alpha = std::min(alpha, x(c) / (x(c) - z(c)));
      x += alpha * (z - x);
      for (int c : set)
        if (x(c) <= 1e-15 * std::max(x.cwiseAbs().maxCoeff(), 1e-300)) in_p[c] = 0, x(c) = 0.0;
    }
  }
  return (J * x + W).norm() <= 1e-9 * W.norm();
}

}  // namespace tumble
