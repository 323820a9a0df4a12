// The step of an island of bodies that meet: today's single-body step (World::advance_body)
// generalised to several bodies, fixed bodies and the floor as shapes of their own.
//
// A step of an island: resting contacts (touching, slow) get inelastic impulses if they still
// approach, then contact forces inside every derivative evaluation (one LCP over the whole
// island); the island is integrated over what is left of the step; the first pair to cross
// (conservative advancement brackets it, regula falsi locates it) ends the stretch there, its
// impacts are resolved over every touching contact of the island, and the step goes on.

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <string>

#include "collide.hpp"
#include "held_rows.hpp"
#include "island.hpp"
#include "lcp.hpp"
#include "number_text.hpp"
#include "time_of_impact.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

using Tol = ContactTolerances;

struct Bounds {
  Vec3 lo, hi;
  bool overlaps(const Bounds& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

// Deterministic union–find: the root of a set is its smallest index.
int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}
void join(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a), b = find_root(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

// The pose of one side of a pair at an island state.
Pose side_pose(const IslandView& v, const Side& s, const IslandState& st) {
  if (s.kind == Side::Member) return pose_of(st[s.index]);
  if (s.kind == Side::Fixed) return pose_of((*v.bodies)[s.index].state);
  return {};
}

// The slip of a contact at state s: the relative velocity of its two surface points (b minus
// a) off the normal.
Vec3 contact_slip(const IslandView& v, const IslandContact& c, const IslandState& s) {
  const IslandPair& p = v.island->pairs[c.pair];
  const ContactFrame f = contact_frame(v, c, s);
  auto point_velocity = [&](const Side& side, const Vec3& r) -> Vec3 {
    if (side.kind != Side::Member) return Vec3::Zero();
    const RigidBody& b = v.member(side.index);
    const Mat3& R = s[side.index].R;
    const Vec3 w = R * b.inverse_inertia_body().asDiagonal() * R.transpose() * s[side.index].L;
    return s[side.index].P * b.inverse_mass() + w.cross(r);
  };
  const Vec3 slip = point_velocity(p.b, f.rb) - point_velocity(p.a, f.ra);
  return slip - f.n * f.n.dot(slip);
}

// Contacts of one symmetric pose (the two ends of a domino's edge, a box's four corners) reach
// a mode change together, their ratios equal but for round-off: taking them one at a time, in
// index order, would free one end and keep the other, a lopsided answer that turns a planar
// scene out of its plane. A ratio within 1e-6 of the worst counts as tied with it.
bool tied(double ratio, double worst) {
  return ratio >= worst * (1.0 - 1e-6);
}

// Static friction inside a stretch holds a sticking contact with whatever tangential force
// it takes; one that needs more than mu times its normal force (or presses not at all) slides
// instead. The furthest outside its cone first (with those tied with it; freeing one changes
// what the others need), until every sticking contact's force is inside its cone: the modes are
// fixed here, where the stretch starts, and not inside its stages (a mode switch there makes the
// derivative jump). `forces` are those of the modes it ends with. Returns the contacts it set
// sliding, frictionless until aim_freed gives them their way.
std::vector<std::size_t> hold_or_slip(const IslandView& v, const IslandDynamics& dynamics,
                                      std::vector<IslandContact>& held, const IslandState& s,
                                      IslandDynamics::HeldForces& forces) {
  std::vector<std::size_t> freed;
  forces = dynamics.held_forces(s);
  bool any = false;
  for (const IslandContact& c : held) any |= !c.sliding && v.island->pairs[c.pair].friction > 0.0;
  for (std::size_t round = 0; any && round < held.size(); ++round) {
    if (round > 0) forces = dynamics.held_forces(s);
    std::vector<double> ratio(held.size(), 0.0);
    double worst = 1.0 + 1e-9;
    for (std::size_t i = 0; i < held.size(); ++i) {
      const double mu = v.island->pairs[held[i].pair].friction;
      const double ft = forces.friction[i].norm();
      if (held[i].sliding || !(mu > 0.0) || !(ft > 0.0)) continue;
      const double cap = mu * forces.normal(static_cast<Eigen::Index>(i));
      ratio[i] = cap > 0.0 ? ft / cap : INFINITY;
      worst = std::max(worst, ratio[i]);
    }
    if (!(worst > 1.0 + 1e-9)) break;
    for (std::size_t i = 0; i < held.size(); ++i)
      if (ratio[i] > 1.0 + 1e-9 && tied(ratio[i], worst)) {
        held[i].sliding = true;
        held[i].fixed_slip = true;
        held[i].slip_direction.setZero();
        freed.push_back(i);
      }
  }
  if (!freed.empty()) forces = dynamics.held_forces(s);
  return freed;
}

// The impulse that stops the slip of the held contacts taken as sticking, bounded by what
// their friction has left over the coming stretch once it holds them (mu f_n − |f_t|, times
// tau; `forces` are hold_or_slip's), applied with the normal impulses redistributed
// (restore_normal_speeds). Where no such impulse exists, contacts are set sliding (added to
// `freed`, for aim_freed) until it does. A slip below `still` (per contact) is round-off of a
// held one, whose direction is noise: left alone.
void stop_sticking_slip(const IslandView& v, const IslandDynamics::HeldForces& forces,
                        std::vector<IslandContact>& held, const std::vector<double>& still,
                        double tau, IslandState& s, std::vector<std::size_t>& freed) {
  std::vector<std::size_t> which;
  for (std::size_t i = 0; i < held.size(); ++i)
    if (!held[i].sliding && v.island->pairs[held[i].pair].friction > 0.0 &&
        contact_slip(v, held[i], s).norm() > still[i])
      which.push_back(i);
  if (which.empty()) return;
  const Eigen::VectorXd& force = forces.normal;
  // Where the joint impulse leaves a cone, the contact whose slip is largest against what its
  // friction has left (with those tied with it) slides, and the others are tried again: a foot
  // that cannot be stopped does not set its neighbours sliding at slips they stop in the stretch.
  // (Kinetic friction at a slip that reverses inside the stretch points along the slip's
  // round-off: it would turn a planar row of dominoes out of its plane.)
  while (!which.empty()) {
    std::vector<IslandContact> sticking;
    std::vector<double> impulse;
    for (std::size_t i : which) {
      sticking.push_back(held[i]);
      const double mu = v.island->pairs[held[i].pair].friction;
      impulse.push_back(
          std::max(0.0, force(static_cast<Eigen::Index>(i)) - forces.friction[i].norm() / mu) *
          tau);
    }
    IslandState stopped = s;
    if (apply_island_friction(v, sticking, impulse, stopped)) {
      std::vector<double> loads;
      for (Eigen::Index i = 0; i < force.size(); ++i) loads.push_back(force(i) * tau);
      restore_normal_speeds(v, held, loads, stopped);
      s = stopped;
      return;
    }
    std::vector<double> ratio;
    double worst = 0.0;
    for (std::size_t i : which) {
      const double cap =
          v.island->pairs[held[i].pair].friction * force(static_cast<Eigen::Index>(i)) -
          forces.friction[i].norm();
      const double slip = contact_slip(v, held[i], s).norm();
      ratio.push_back(cap > 0.0 ? slip / cap : INFINITY);
      worst = std::max(worst, ratio.back());
    }
    std::vector<std::size_t> rest;
    for (std::size_t k = 0; k < which.size(); ++k) {
      if (!tied(ratio[k], worst)) {
        rest.push_back(which[k]);
        continue;
      }
      IslandContact& c = held[which[k]];
      c.sliding = true;
      c.fixed_slip = true;
      c.slip_direction.setZero();
      freed.push_back(which[k]);
    }
    which = rest;
  }
}

// The way the contacts set sliding at a stretch's start go, fixed for the stretch: their slip
// is small (they were taken as sticking) and may reverse inside it, where its direction is
// round-off. They go the way their slip would be at the stretch's end if they were
// frictionless, slip + tau · (its rate now): down the slope for a box set on a steep ramp; the
// way it slips for a slip that the stretch does not reverse.
void aim_freed(const IslandView& v, const IslandDynamics& dynamics,
               std::vector<IslandContact>& held, const std::vector<std::size_t>& freed, double tau,
               const IslandState& s) {
  if (freed.empty()) return;
  const std::vector<Vec3> rate = dynamics.slip_accelerations(s);
  for (std::size_t i : freed) {
    const Vec3 way = contact_slip(v, held[i], s) + tau * rate[i];
    if (way.norm() > 0.0) held[i].slip_direction = way.normalized();
  }
}

// A held pair still overlapping after the drift correction's pass: its normal (from a to b)
// and how deep its deepest held contact is (negative: apart by that much).
struct HeldPush {
  int pair = 0;
  Vec3 n = Vec3::Zero();
  double depth = 0.0;
};

// The least move of the members, in the mass metric (the sum of m |dx|^2), that parts every
// held pair by its depth: translations along the normals, dx_k = (1/m_k) sum_i s_ik l_i n_i
// with l >= 0 complementary to n_i . (dx_b - dx_a) >= depth_i, an LCP over the pairs whose
// matrix is that of impulses on point masses (symmetric, semidefinite). Member order.
std::vector<std::pair<int, Vec3>> project_held_apart(const IslandView& v,
                                                     const std::vector<HeldPush>& rows) {
  const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
  // The members a row pushes, with the sign of its push on each (b +1, a -1).
  auto sides = [&](std::size_t i) {
    const IslandPair& p = v.island->pairs[static_cast<std::size_t>(rows[i].pair)];
    std::array<std::pair<int, double>, 2> out{{{-1, 0.0}, {-1, 0.0}}};
    if (p.a.kind == Side::Member) out[0] = {p.a.index, -1.0};
    out[1] = {p.b.index, 1.0};
    return out;
  };
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto si = sides(static_cast<std::size_t>(i));
    b(i) = -rows[static_cast<std::size_t>(i)].depth;
    for (Eigen::Index j = 0; j < n; ++j)
      for (const auto& [mi, sgi] : sides(static_cast<std::size_t>(j)))
        for (const auto& [mk, sgk] : si)
          if (mi >= 0 && mi == mk)
            A(i, j) += sgi * sgk * v.member(mi).inverse_mass() *
                       rows[static_cast<std::size_t>(i)].n.dot(rows[static_cast<std::size_t>(j)].n);
  }
  Eigen::VectorXd l;
  std::vector<char> active;
  solve_lcp_pivoting(A, b, l, active, /*ridge_on_stall=*/true, /*last_resort=*/true);
  std::vector<Vec3> dx(v.island->members.size(), Vec3::Zero());
  std::vector<char> moved(dx.size(), 0);
  for (Eigen::Index i = 0; i < l.size(); ++i)
    for (const auto& [m, sg] : sides(static_cast<std::size_t>(i)))
      if (m >= 0 && l(i) > 0.0) {
        dx[static_cast<std::size_t>(m)] +=
            sg * l(i) * v.member(m).inverse_mass() * rows[static_cast<std::size_t>(i)].n;
        moved[static_cast<std::size_t>(m)] = 1;
      }
  std::vector<std::pair<int, Vec3>> out;
  for (std::size_t m = 0; m < dx.size(); ++m)
    if (moved[m]) out.emplace_back(static_cast<int>(m), dx[m]);
  return out;
}

// Mid-step states carry unnormalised quaternions: collision geometry wants a rotation.
void normalize(BodyState& b, RotationRep rep) {
  if (rep == RotationRep::Quaternion) b.R = b.q.normalized().toRotationMatrix();
}

IslandState normalized(const IslandState& s, RotationRep rep) {
  IslandState out = s;
  for (BodyState& b : out) normalize(b, rep);
  return out;
}

}  // namespace

std::vector<Island> World::find_islands(double h) {
  const std::size_t n = bodies_.size();
  const double g = def_.gravity.norm();
  // An impact inside the step can set a body still at its start moving: at most about twice
  // the fastest point's speed in the world (a light body struck by a heavy one). Every moving
  // body's bounds cover that reach, so a chain of bodies struck within one step is one island
  // (and the candidates below take it island by island).
  double fastest = 0.0;
  std::vector<double> speed(n, 0.0);  // each moving body's fastest point
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& b = bodies_[i];
    if (b.is_fixed() || b.at_rest) continue;
    speed[i] = b.velocity().norm() + b.angular_velocity().norm() * b.bounding_radius();
    fastest = std::max(fastest, speed[i]);
  }
  std::vector<Bounds> bounds(n);
  // How far any point of each body can go by turning within the step: |ω| h r, |ω| at most
  // |L| over the smallest moment of inertia, and never more than 2 r.
  std::vector<double> turn(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& b = bodies_[i];
    // The body's world box (for a thin body much tighter than its bounding sphere: a row of
    // dominoes is not one island) and its touch distance.
    const Vec3 extent =
        b.half_extent_world(b.state.R) + Vec3::Constant(tolerances_[i].touch_m);
    Vec3 from = b.state.x, to = b.state.x;
    double grow = 0.0;
    if (!b.is_fixed() && !b.at_rest) {
      // Where free flight takes the centre over h, grown by what forces other than gravity
      // (contacts, drag) could add within the step: half the speed again, and g h² — generous,
      // so no pair that meets within the step is missed by the broad phase.
      const Vec3 v = b.velocity();
      to = from + h * v + (0.5 * h * h) * def_.gravity;
      grow += 0.5 * v.norm() * h + g * h * h + 2.0 * fastest * h;
    }
    if (!b.is_fixed() && !b.at_rest)
      turn[i] = std::min(b.state.L.norm() * b.inverse_inertia_body().maxCoeff() * h, 2.0) *
                b.bounding_radius();
    // Turning, a point of the body moves at most |ω| h r within the step (what an impact adds
    // is in `grow`); the box never needs to be larger than the bounding sphere.
    Vec3 half = extent;
    if (!b.is_fixed() && !b.at_rest)
      half = (extent + Vec3::Constant(b.angular_velocity().norm() * h * b.bounding_radius()))
                 .cwiseMin(Vec3::Constant(b.bounding_radius() + tolerances_[i].touch_m));
    bounds[i] = {from.cwiseMin(to) - half - Vec3::Constant(grow),
                 from.cwiseMax(to) + half + Vec3::Constant(grow)};
  }
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  // Broad phase: sort and sweep along x. The bodies in the order of their bounds' low x (ties
  // by index); each is compared only with those after it that start before it ends. The pairs
  // whose bounds overlap are then put in (i, j) order, so what follows never depends on where
  // the bodies are: n log n plus the pairs that overlap in x, instead of every pair.
  std::vector<int> by_x(n);
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](int i, int j) {
    return bounds[i].lo.x() < bounds[j].lo.x() || (bounds[i].lo.x() == bounds[j].lo.x() && i < j);
  });
  std::vector<std::pair<int, int>> overlapping;  // (i, j), i < j, bounds overlapping
  for (std::size_t a = 0; a < n; ++a) {
    const int i = by_x[a];
    for (std::size_t b = a + 1; b < n && bounds[by_x[b]].lo.x() <= bounds[i].hi.x(); ++b) {
      const int j = by_x[b];
      if (bodies_[i].is_fixed() && bodies_[j].is_fixed()) continue;
      if (bounds[i].overlaps(bounds[j]) && pair_collides(std::min(i, j), std::max(i, j)))
        overlapping.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(overlapping.begin(), overlapping.end());
  // Bounds are boxes about the bodies, and a turned die's box reaches up to 0.17 m from its
  // centre where its faces are 0.1 m away: the hundred dice, 0.3 m apart on their
  // lattice and spinning, had overlapping boxes within a tenth of a second, and at 0.1 s 80 of
  // them were one island of 222 pairs, none touching (an impact restarts a whole island's
  // stretch; with this, each die is stepped alone there). So a pair whose bounds
  // overlap is a candidate only where the two bodies' separation (a lower bound of their
  // distance) is within what their motion against each other can close in the step. Two
  // bodies in free flight fall together: one moves against the other at v_b − v_a, and a point
  // turns by at most its body's `turn`; against a fixed body, v h + g h² / 2. A body that
  // something can act on within the step (the floor its bounds reach, a drag, a candidate
  // pair, a resting body's support) may leave its free flight by what the bounds grow by for
  // it: half its speed and g h² for forces, and for an impact twice the fastest point's
  // speed, not in the world, but in its island (no faster body can strike it within the step
  // without being a candidate of the island). Islands only merge, speeds only grow and bodies
  // only become acted on as candidates are found, so this is repeated until nothing changes.
  // A sleeping body that an awake one can reach is woken (and its touching neighbours with it,
  // pass after pass).
  std::vector<char> acted(n, 0);
  const bool drag = def_.linear_drag > 0.0 || def_.angular_drag > 0.0;
  for (std::size_t i = 0; i < n; ++i)
    acted[i] = drag || bodies_[i].at_rest ||
               (def_.floor && bounds[i].lo.y() <= def_.floor->height &&
                pair_collides(kFloorBody, static_cast<int>(i)));
  std::vector<double> gap(overlapping.size(), NAN);  // measured when first needed
  std::vector<double> island_speed(n);
  auto meets = [&](std::size_t k) {
    const auto [i, j] = overlapping[k];
    const RigidBody &a = bodies_[i], &b = bodies_[j];
    if (std::isnan(gap[k])) gap[k] = separation(a, pose_of(a.state), b, pose_of(b.state));
    double closing = tolerances_[i].touch_m + tolerances_[j].touch_m + turn[i] + turn[j];
    closing += a.is_fixed() || b.is_fixed()
                   ? (a.velocity() + b.velocity()).norm() * h + 0.5 * g * h * h
                   : (b.velocity() - a.velocity()).norm() * h;
    for (int x : {i, j}) {
      const RigidBody& body = bodies_[x];
      if (body.is_fixed() || !acted[x]) continue;
      closing += 0.5 * body.velocity().norm() * h + g * h * h +
                 2.0 * island_speed[find_root(parent, x)] * h;
    }
    return gap[k] <= closing;
  };
  std::vector<std::pair<int, int>> candidates;  // the pairs that can meet, one side moving
  for (bool changed = true; changed;) {
    changed = false;
    std::fill(island_speed.begin(), island_speed.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const int root = find_root(parent, static_cast<int>(i));
      island_speed[root] = std::max(island_speed[root], speed[i]);
    }
    candidates.clear();
    for (std::size_t k = 0; k < overlapping.size(); ++k) {
      const auto [i, j] = overlapping[k];
      RigidBody &a = bodies_[i], &b = bodies_[j];
      const bool a_moves = !a.is_fixed() && !a.at_rest, b_moves = !b.is_fixed() && !b.at_rest;
      if ((!a_moves && !b_moves) || !meets(k)) continue;
      candidates.emplace_back(i, j);
      for (RigidBody* x : {&a, &b})
        if (x->at_rest && !x->is_fixed()) x->at_rest = false, changed = true;
      for (int x : {i, j})
        if (!acted[x]) acted[x] = 1, changed = true;
      if (!a.is_fixed() && !b.is_fixed() && find_root(parent, i) != find_root(parent, j)) {
        join(parent, i, j);
        changed = true;
      }
    }
  }
  // Islands in the order of their smallest member; members ascending.
  std::vector<Island> islands;
  std::vector<int> island_of(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& b = bodies_[i];
    if (b.is_fixed() || b.at_rest) continue;
    const int root = find_root(parent, static_cast<int>(i));
    if (island_of[root] < 0) {
      island_of[root] = static_cast<int>(islands.size());
      islands.emplace_back();
    }
    islands[island_of[root]].members.push_back(static_cast<int>(i));
  }
  auto local = [&](const Island& isl, int body) {
    return static_cast<int>(std::lower_bound(isl.members.begin(), isl.members.end(), body) -
                            isl.members.begin());
  };
  for (const auto& [i, j] : candidates) {
    const bool fi = bodies_[i].is_fixed(), fj = bodies_[j].is_fixed();
    const int moving = fi ? j : i;
    Island& isl = islands[island_of[find_root(parent, moving)]];
    IslandPair p;
    const auto [e, mu] = pair_material(i, j);
    p.restitution = e, p.friction = mu;
    if (fi || fj) {
      const int still = fi ? i : j;
      p.a = {Side::Fixed, still};
      p.b = {Side::Member, local(isl, moving)};
      p.body_a = still, p.body_b = moving;
    } else {
      p.a = {Side::Member, local(isl, i)};
      p.b = {Side::Member, local(isl, j)};
      p.body_a = i, p.body_b = j;
    }
    isl.pairs.push_back(p);
  }
  for (Island& isl : islands) {
    if (!def_.floor) continue;
    for (std::size_t k = 0; k < isl.members.size(); ++k) {
      const int body = isl.members[k];
      if (!pair_collides(kFloorBody, body)) continue;
      IslandPair p;
      const auto [e, mu] = pair_material(kFloorBody, body);
      p.restitution = e, p.friction = mu;
      p.a = {Side::Floor, 0};
      p.b = {Side::Member, static_cast<int>(k)};
      p.body_a = kFloorBody, p.body_b = body;
      isl.pairs.push_back(p);
    }
  }
  return islands;
}

void World::advance_all(double h) {
  if (!meets_bodies_) {
    for (std::size_t i = 0; i < bodies_.size(); ++i) advance_body(i, h);
    return;
  }
  // Every body asleep or fixed: nothing moves and nothing can wake them (only an awake body's
  // bounds do), so the broad phase has nothing to find. A resting pile of a thousand boxes then
  // costs nothing a step, where sorting its touching pairs cost 150 µs.
  if (std::all_of(bodies_.begin(), bodies_.end(),
                  [](const RigidBody& b) { return b.is_fixed() || b.at_rest; }))
    return;
  for (const Island& island : find_islands(h)) {
    // A body alone, meeting at most the floor: the single-body step, exactly as before.
    const bool alone = island.members.size() == 1 &&
                       std::all_of(island.pairs.begin(), island.pairs.end(),
                                   [](const IslandPair& p) { return p.a.kind == Side::Floor; });
    if (alone)
      advance_body(static_cast<std::size_t>(island.members[0]), h);
    else
      advance_island(island, h);
  }
}

void World::advance_island(const Island& island, double h) {
  const ForceModel forces{def_.gravity, def_.linear_drag, def_.angular_drag,
                          def_.general_contact_only};
  IslandView view{&bodies_, &island, def_.rotation, &forces};
  const int members = static_cast<int>(island.members.size());
  IslandState state(static_cast<std::size_t>(members));
  for (int k = 0; k < members; ++k) state[k] = bodies_[island.members[k]].state;

  // Tolerances of a pair: the finer of its two bodies' (a fixed body or the floor: the moving
  // one's), so a small body meeting a large one keeps its own precision.
  auto tol_of = [&](const IslandPair& p) {
    Tol t = tolerances_[p.body_b];
    if (p.body_a >= 0 && !bodies_[p.body_a].is_fixed()) {
      const Tol& o = tolerances_[p.body_a];
      t.toi_time_s = std::min(t.toi_time_s, o.toi_time_s);
      t.touch_m = std::min(t.touch_m, o.touch_m);
      t.rest_speed_mps = std::max(t.rest_speed_mps, o.rest_speed_mps);
      t.hold_speed_mps = std::min(t.hold_speed_mps, o.hold_speed_mps);
      t.lift_speed_mps = std::min(t.lift_speed_mps, o.lift_speed_mps);
      t.sleep_speed_mps = std::min(t.sleep_speed_mps, o.sleep_speed_mps);
      t.length_m = std::min(t.length_m, o.length_m);
    }
    return t;
  };
  std::vector<Tol> pair_tol;
  for (const IslandPair& p : island.pairs) pair_tol.push_back(tol_of(p));

  // `axis`, where given: the axis the separation is measured along (from a towards b).
  auto pair_separation = [&](std::size_t p, const IslandState& s, Vec3* axis = nullptr) {
    const IslandPair& pr = island.pairs[p];
    const Pose pb = pose_of(s[pr.b.index]);
    const RigidBody& B = *view.side_body(pr.b);
    if (pr.a.kind == Side::Floor) {
      if (axis) *axis = Vec3::UnitY();
      return plane_separation(def_.floor->height, B, pb);
    }
    return separation(*view.side_body(pr.a), side_pose(view, pr.a, s), B, pb, axis);
  };
  // Every contact point of the island within each pair's touch distance, in pair order.
  auto find_contacts = [&](const IslandState& s) {
    std::vector<IslandContact> out;
    for (std::size_t p = 0; p < island.pairs.size(); ++p) {
      const IslandPair& pr = island.pairs[p];
      const RigidBody& B = *view.side_body(pr.b);
      const Pose pb = pose_of(s[pr.b.index]);
      const Pose pa = side_pose(view, pr.a, s);
      const Manifold m = pr.a.kind == Side::Floor
                             ? collide_plane(def_.floor->height, B, pb, pair_tol[p].touch_m)
                             : collide(*view.side_body(pr.a), pa, B, pb, pair_tol[p].touch_m);
      const RigidBody* A = view.side_body(pr.a);
      for (int i = 0; i < m.count; ++i) {
        IslandContact c;
        c.pair = static_cast<int>(p);
        c.feature = m.points[i].feature;
        c.radius_a = A && A->is_sphere() ? A->radius() : 0.0;
        c.radius_b = B.is_sphere() ? B.radius() : 0.0;
        c.anchor_a = pr.a.kind == Side::Floor ? m.points[i].on_a
                                              : Vec3(pa.R.transpose() * (m.points[i].on_a - pa.x));
        c.anchor_b = pb.R.transpose() * (m.points[i].on_b - pb.x);
        if (m.normal_of_b) {
          c.normal_on = pr.b.index;
          c.normal_local = pb.R.transpose() * m.normal;
        } else if (pr.a.kind == Side::Member) {
          c.normal_on = pr.a.index;
          c.normal_local = pa.R.transpose() * m.normal;
        } else {
          c.normal_on = -1;
          c.normal_local = m.normal;
        }
        if (m.edges) {
          c.edge_edge = true;
          c.edge_a_local = pa.R.transpose() * m.edge_a;
          c.edge_b_local = pb.R.transpose() * m.edge_b;
          c.edge_sign = m.edge_a.cross(m.edge_b).dot(m.normal) >= 0.0 ? 1.0 : -1.0;
        }
        out.push_back(c);
      }
      if (m.count > 0) pair_stats(pr.body_a, pr.body_b);  // touched
    }
    return out;
  };
  // At a normalised state (`posed`).
  auto separation_of = [&](const IslandContact& c, const IslandState& posed) {
    const ContactFrame f = contact_frame(view, c, posed);
    return f.n.dot(f.pb - f.pa);
  };
  auto write_back = [&] {
    for (int k = 0; k < members; ++k) bodies_[island.members[k]].state = state[k];
  };

  const int first = island.members.front();
  Stepping how = stepping(static_cast<std::size_t>(first));
  std::vector<Stepping> per_body;
  for (int body : island.members) per_body.push_back(stepping(static_cast<std::size_t>(body)));
  double speed_scale = 0.0, noise_scale = 0.0;
  for (int body : island.members) {
    speed_scale = std::max(speed_scale, tolerances_[body].rest_speed_mps);
    noise_scale = std::max(noise_scale, tolerances_[body].length_m);
  }

  // At rest already? Every member slow and the island in equilibrium on its contacts (with
  // static friction inside its cones): its exact motion is then none, and it sleeps.
  {
    const std::vector<IslandContact> touching = find_contacts(state);
    bool slow = !touching.empty() && def_.gravity.norm() > 0.0;
    for (int k = 0; k < members && slow; ++k) {
      const RigidBody& b = view.member(k);
      const Mat3 R = state[k].R;
      const Vec3 w = R * b.inverse_inertia_body().asDiagonal() * R.transpose() * state[k].L;
      slow = state[k].P.norm() * b.inverse_mass() + w.norm() * b.bounding_radius() <=
             tolerances_[island.members[k]].sleep_speed_mps;
    }
    if (slow && island_in_equilibrium(view, touching, state)) {
      for (int k = 0; k < members; ++k) {
        RigidBody& b = bodies_[island.members[k]];
        b.state.P.setZero();
        b.state.L.setZero();
        b.at_rest = true;
      }
      return;
    }
  }

  double remaining = h;
  int events = 0;
  // The event budget of a step grows with the island: a pile of a hundred dice landing has
  // that many first meetings in a step, each an impact of its own.
  const int budget = Tol::kMaxEventsPerStep * ((members + 15) / 16);
  bool contact = false;
  bool solve_failed = false;
  bool settle = false, blind = false;
  std::vector<char> active;
  HeldRowsCache rows_cache;
  std::vector<std::pair<int, std::uint32_t>> active_of;  // the contacts `active` is for
  // Per pair, how much deeper than it starts a stretch it may go before it is an impact (see
  // "Every pair is watched" below): raised for the rest of the step after an empty event.
  std::vector<double> slack(island.pairs.size(), 0.0);
  while (remaining > 0.0) {
    if (def_.poll && events > 0) def_.poll();
    std::vector<IslandContact> touching = find_contacts(state);
    std::vector<IslandContact> held;
    std::vector<char> pair_held(island.pairs.size(), 0), pair_touching(island.pairs.size(), 0);
    for (const IslandContact& c : touching) pair_touching[c.pair] = 1;
    if (!touching.empty()) {
      contact = true;
      std::vector<IslandContact> resting;
      for (const IslandContact& c : touching)
        if (settle || std::abs(normal_speed(view, c, state)) <= pair_tol[c.pair].rest_speed_mps)
          resting.push_back(c);
      if (!resting.empty()) {
        std::vector<double> impulses;
        stats_.max_energy_gain_J =
            std::max(stats_.max_energy_gain_J,
                     resolve_island_impacts(view, resting, state, INFINITY, true, impulses));
      }
      // A point that leaves slower than the lift speed would rise at most 1e-9 of the pair's
      // size and come back as an impact: in a landing pile of 27 dice, 65 % of the impacts came
      // in slower than 1e-4 m/s, dice rocking between the points of a face or an edge, each
      // one restarting the island's stretch. Such points are stopped with the held ones (the
      // Zeno limit of that rocking, as resolve_island_impacts takes it below the rest speed:
      // a projection in the kinetic metric, which never gains energy).
      {
        std::vector<IslandContact> slow;
        bool lifting = false;
        for (const IslandContact& c : resting) {
          const double vn = normal_speed(view, c, state);
          if (std::abs(vn) <= pair_tol[c.pair].lift_speed_mps) {
            slow.push_back(c);
            lifting |= vn > pair_tol[c.pair].hold_speed_mps;
          }
        }
        if (lifting) stop_island_points(view, slow, state);
      }
      for (IslandContact& c : resting)
        if (normal_speed(view, c, state) <= pair_tol[c.pair].hold_speed_mps) {
          pair_held[c.pair] = 1;
          held.push_back(c);
        }
    }
    // Sliding: the slip against what friction could remove over the stretch, 2 mu g τ.
    for (IslandContact& c : held) {
      const IslandPair& p = island.pairs[c.pair];
      if (p.friction <= 0.0) continue;
      const double dv = def_.gravity.norm() * remaining;
      const Vec3 slip = contact_slip(view, c, state);
      c.sliding = slip.norm() > 2.0 * p.friction * dv;
    }
    // The last clamped set is a warm start for the same contacts only: with sliding friction
    // the LCP can have several solutions, and another set's (of the same size) picks one
    // that holds a domino's edge by one end. A new set starts from all clamped.
    std::vector<std::pair<int, std::uint32_t>> held_ids;
    for (const IslandContact& c : held) held_ids.emplace_back(c.pair, c.feature);
    if (held_ids != active_of) active.clear();
    active_of = held_ids;
    const IslandDynamics dynamics(view, &held, &active, &evaluations_, &solve_failed, &rows_cache);
    // Static friction inside the stretch holds a sticking contact's slip where it is. Which
    // contacts it can hold is found first (hold_or_slip: a box set on a ramp steeper than atan
    // mu cannot be held); the slip of those it holds is then stopped by an impulse within what
    // their friction has left over the stretch, and those it cannot stop slide.
    // A slip slower than 1e-3 of the hold speed (1 nm/s at 1 m) is round-off of a contact
    // held sticking (rk4's drift of a held point: ~1e-15 of its size a step).
    std::vector<double> still;
    for (const IslandContact& c : held) still.push_back(1e-3 * pair_tol[c.pair].hold_speed_mps);
    IslandDynamics::HeldForces holding;
    std::vector<std::size_t> freed = hold_or_slip(view, dynamics, held, state, holding);
    stop_sticking_slip(view, holding, held, still, remaining, state, freed);
    aim_freed(view, dynamics, held, freed, remaining, state);
    const IslandState start = state;
    auto advanced = [&](double tau, StepInfo* info) {
      return integrate_island(dynamics, start, tau, how, per_body, info);
    };
    double tau = remaining;
    StepInfo end_info;
    IslandState end = advanced(tau, &end_info);

    // Impacts: the pairs that do not rest on each other now, watched for a crossing.
    // Every pair is watched. One that starts overlapping (a drifted contact) is watched for
    // going deeper than it started: its gap is measured from its start's overlap. A pair held
    // by contact forces keeps its held points at zero separation to round-off (rk4 drift of a
    // held point: ~1e-15 ℓ a step); another point of it (a corner rocking down onto the same
    // face) is an impact once it is 1e-3 of the touch distance (1e-9 ℓ) deep: far above the
    // held points' drift, and far below anything a lift or an impact there could make visible.
    std::vector<std::size_t> watched;
    std::vector<double> gap_start, gap_offset;
    std::vector<Vec3> axis_start;
    // After the event budget (settled, below), the touching pairs are held and an impact only
    // once they are the touch distance deeper than the stretch starts, and the pairs apart at
    // its start are watched as before: a new meeting is an impact still, resolved inelastically.
    // Unwatched, a pile of a hundred dice that spent its budget let six pairs 0.03–2.4 mm apart
    // go 0.57 mm through each other within the step, and the next step's correction gained
    // 0.043 J; and a die held at one corner on another, whose far corner came down at 1.2 m/s,
    // went 0.3 mm into it (the pile of 27 dice: the budget spent on a corner that rocked
    // between two points of a face at 1.7e-6 m/s, every 2e-7 s).
    // A pair whose touching points approach at the stretch's start (faster than they could be
    // held) is an impact now, found at once: no slack for it.
    std::vector<char> approaching(island.pairs.size(), 0);
    for (const IslandContact& c : touching)
      if (-normal_speed(view, c, start) > pair_tol[c.pair].hold_speed_mps) approaching[c.pair] = 1;
    std::vector<double> sep_start;  // each pair's separation at the stretch's start
    for (std::size_t p = 0; p < island.pairs.size(); ++p) {
      Vec3 axis;
      const double g = pair_separation(p, start, &axis);
      sep_start.push_back(g);
      watched.push_back(p);
      axis_start.push_back(axis);
      // How much deeper than it starts it may go: 1e-3 of the touch distance where it is held;
      // the touch distance after the budget or an empty event of the pair (below), but not
      // where its touching points approach: a die landing on the floor at 0.09 m/s in a tower of
      // three, after an empty event of the same pair earlier in the step, met the floor 2e-7 m
      // deep, and 4e-7 m at the next impact, whose correction gained 3e-5 J. (Measured from
      // zero instead of from the start, the slack held a pair whose separating-axis value sat
      // at the touch distance while its points did not approach in an empty event every 2e-12 s,
      // until the budget was spent.)
      // The slack is for a pair that starts the stretch in contact (within its touch distance):
      // one apart is an impact at its first meeting. A pair marked in an event's search (found
      // across on a trial state) but 62 µm apart where the search ended met the next domino
      // with the slack, 4.8e-8 m deep, and its correction gained 2.6e-9 J.
      const double allowed = settle && pair_touching[p] ? pair_tol[p].touch_m
                             : pair_held[p]             ? 1e-3 * pair_tol[p].touch_m
                                                        : 0.0;
      const bool slack_applies = !approaching[p] && g <= pair_tol[p].touch_m;
      gap_offset.push_back(std::min(g, 0.0) - std::max(slack_applies ? slack[p] : 0.0, allowed));
      gap_start.push_back(g - gap_offset.back());
    }
    auto pair_gap = [&](std::size_t w, const IslandState& s, Vec3* axis = nullptr) {
      return pair_separation(watched[w], s, axis) - gap_offset[w];
    };
    bool impact = false;
    std::vector<std::size_t> crossed_pairs;
    if (!watched.empty() && !blind) {
      // A bound on how fast each pair's separation can shrink: the relative speed of their
      // centres plus each one's spin times its reach, the larger of the stretch's two ends
      // (under a constant force a speed is largest at an end), with a 25 % margin for the
      // contact forces' variation within the stretch. The separation is Lipschitz with it.
      auto omega = [&](const IslandState& s, const Side& side) {
        if (side.kind != Side::Member) return Vec3(Vec3::Zero());
        const RigidBody& b = view.member(side.index);
        const Mat3 R = rotation_of(s[side.index], def_.rotation);
        return Vec3(R * b.inverse_inertia_body().asDiagonal() * R.transpose() * s[side.index].L);
      };
      auto body_speed = [&](const IslandState& s, const Side& side) {
        if (side.kind != Side::Member) return std::pair(Vec3(Vec3::Zero()), 0.0);
        const RigidBody& b = view.member(side.index);
        // Turning a ball or a point about its centre does not move its surface.
        const double reach = b.is_sphere() || b.is_particle() ? 0.0 : b.bounding_radius();
        return std::pair(Vec3(s[side.index].P * b.inverse_mass()), omega(s, side).norm() * reach);
      };
      auto reach_of = [&](const Side& side) {
        return side.kind == Side::Member ? view.member(side.index).bounding_radius() : 0.0;
      };
      // Two bodies' velocity fields differ by a rigid motion: at any point p, b moves against a
      // at v_rel(c) + (ω_b − ω_a) × (p − c) from a point c, which for c = x_b is
      // v_b − v_a − ω_a × (x_b − x_a), and |p − x_b| <= b's reach where b has its closest
      // point. The closest points differ by the gap d, whose direction turns with a:
      // |ω_a| d more. The smaller of the two ways round (c = x_a likewise), for two boxes:
      // dominoes falling against each other turn and move nearly together, and this is a
      // fraction of what each one's own speed is.
      const IslandState end_n = normalized(end, def_.rotation);
      auto relative_bound = [&](const IslandState& s, const IslandPair& p, double d) -> double {
        if (p.a.kind != Side::Member) return INFINITY;
        const RigidBody& A = view.member(p.a.index);
        const RigidBody& B = view.member(p.b.index);
        if (A.is_sphere() || A.is_particle() || B.is_sphere() || B.is_particle()) return INFINITY;
        const BodyState& sa = s[p.a.index];
        const BodyState& sb = s[p.b.index];
        const Vec3 va = sa.P * A.inverse_mass(), vb = sb.P * B.inverse_mass();
        const Vec3 wa = omega(s, p.a), wb = omega(s, p.b);
        const double from_b = (vb - va - wa.cross(sb.x - sa.x)).norm() +
                              (wb - wa).norm() * B.bounding_radius() + wa.norm() * d;
        const double from_a = (va - vb - wb.cross(sa.x - sb.x)).norm() +
                              (wa - wb).norm() * A.bounding_radius() + wb.norm() * d;
        return std::min(from_b, from_a);
      };
      std::vector<double> bound(watched.size());
      // Each pair's separation and its axis at the stretch's end, kept for the advancement's
      // last measurement there (every pair, on the same state).
      std::vector<double> sep_end(watched.size());
      std::vector<Vec3> axis_end_n(watched.size());
      for (std::size_t w = 0; w < watched.size(); ++w)
        sep_end[w] = pair_separation(watched[w], end_n, &axis_end_n[w]);
      for (std::size_t w = 0; w < watched.size(); ++w) {
        const IslandPair& p = island.pairs[watched[w]];
        double worst = 0.0;
        // The gap over which the bound is used: at most the larger end's, and what the
        // advancement lets it close by (the touch distance, or 1e-4 of the size when touching).
        const double d = std::max({sep_start[w], sep_end[w], 0.0}) +
                         std::max(pair_tol[watched[w]].touch_m, 1e-4 * pair_tol[watched[w]].length_m);
        for (const IslandState* s : {&start, &end_n}) {
          const auto [va, spin_a] = body_speed(*s, p.a);
          const auto [vb, spin_b] = body_speed(*s, p.b);
          // A held pair slides on its contact plane: its gap changes only by the motion along
          // the normal of its held points, or by turning. Turning is the one relative to the
          // other: a point p moves against the other body at v(c) + (ω_b − ω_a) × (p − c)
          // from a held point c (rigid kinematics), and |p − c| is at most c's lever plus
          // the body's reach. Two dominoes that fall leaning on each other turn together:
          // their relative turning is a fraction of either's.
          double closing = (vb - va).norm();
          double turning = spin_a + spin_b;
          if (pair_held[watched[w]]) {
            closing = 0.0;
            double lever = 0.0;
            for (const IslandContact& c : held)
              if (static_cast<std::size_t>(c.pair) == watched[w]) {
                closing = std::max(closing, std::abs(normal_speed(view, c, *s)));
                const ContactFrame f = contact_frame(view, c, *s);
                lever = std::max({lever, f.ra.norm() + reach_of(p.a), f.rb.norm() + reach_of(p.b)});
              }
            turning = std::min(turning, (omega(*s, p.b) - omega(*s, p.a)).norm() * lever);
          }
          worst = std::max(worst, std::min(closing + turning, relative_bound(*s, p, d)));
        }
        bound[w] = 1.25 * worst + 1e-300;
      }
      // How fast a pair can close along the axis its gap is measured on (n, from a to b): the
      // two bodies' projections on n are that gap apart, and a point r from a body's centre
      // moves along n at v·n + (ω × r)·n = v·n + r·(n × ω), at most |v·n| + |n × ω| |r|.
      // Against a's centre: |(v_b − v_a)·n| + |n × ω_a| reach_a + |n × ω_b| reach_b, the larger
      // of the stretch's two ends with the same margin. While the pair closes by less than its
      // gap along n it cannot cross (the separating-axis value is no deeper than the overlap on
      // any one axis). Dice that slide past each other, or turn about the axis between them,
      // close along it at a fraction of their speed: where the bounds above took the whole
      // speed, a die beside another that it did not touch cut a 2 ms step into 4 700 pieces.
      struct Motion {
        Vec3 v = Vec3::Zero(), omega = Vec3::Zero();
      };
      std::array<std::vector<Motion>, 2> motion;
      std::vector<double> member_reach(static_cast<std::size_t>(members), 0.0);
      for (int k = 0; k < members; ++k) {
        const RigidBody& b = view.member(k);
        member_reach[static_cast<std::size_t>(k)] =
            b.is_sphere() || b.is_particle() ? 0.0 : b.bounding_radius();
      }
      for (int e = 0; e < 2; ++e) {
        const IslandState& st = e == 0 ? start : end_n;
        for (int k = 0; k < members; ++k) {
          const Side side{Side::Member, k};
          motion[static_cast<std::size_t>(e)].push_back(
              {st[k].P * view.member(k).inverse_mass(), omega(st, side)});
        }
      }
      auto closing_along = [&](std::size_t w, const Vec3& n) {
        const IslandPair& p = island.pairs[watched[w]];
        double worst = 0.0;
        for (const std::vector<Motion>& at : motion) {
          double rate = 0.0;
          Vec3 v = Vec3::Zero();
          for (const Side* side : {&p.a, &p.b}) {
            if (side->kind != Side::Member) continue;
            const Motion& m = at[static_cast<std::size_t>(side->index)];
            v += side == &p.b ? m.v : Vec3(-m.v);
            rate += n.cross(m.omega).norm() * member_reach[static_cast<std::size_t>(side->index)];
          }
          worst = std::max(worst, std::abs(v.dot(n)) + rate);
        }
        return 1.25 * worst + 1e-300;
      };
      // A held point cannot come back down inside the stretch (its row keeps its normal
      // acceleration >= 0, and it starts not approaching). The plane of the face a held pair's
      // normal belongs to has that face's body on one side; for the two to overlap, a point of
      // the other body must go through it, and that body's lowest point against it is a
      // vertex. So the pair is crossed no sooner than its lowest vertex that is not held
      // reaches the plane (a held edge's neighbours turn down only about the edge, no faster
      // than its far vertices, in proportion). A domino tipping on its edge is watched by its
      // lifting back edge, millimetres up, not by the held edge at zero.
      std::vector<std::vector<const IslandContact*>> held_of(island.pairs.size());
      for (const IslandContact& c : held) held_of[c.pair].push_back(&c);
      auto free_gap = [&](std::size_t w, const IslandState& ns) -> double {
        const IslandPair& pr = island.pairs[watched[w]];
        const std::vector<const IslandContact*>& of = held_of[watched[w]];
        if (of.empty()) return -INFINITY;
        const bool face_of_b = of.front()->normal_on == pr.b.index;
        const Side& going = face_of_b ? pr.a : pr.b;  // the body whose vertices go through
        const RigidBody& B = *view.side_body(going);
        if (B.is_sphere() || B.is_particle()) return INFINITY;  // its one point is held
        const Pose pose = side_pose(view, going, ns);
        std::vector<ContactFrame> frames;
        for (const IslandContact* c : of) frames.push_back(contact_frame(view, *c, ns));
        const Vec3 n = face_of_b ? Vec3(-frames.front().n) : frames.front().n;
        const Vec3 on_plane = face_of_b ? frames.front().pb : frames.front().pa;
        const double touch = pair_tol[watched[w]].touch_m;
        double lowest = INFINITY;
        for (const Vec3& v : B.vertices()) {
          const Vec3 p = pose.x + pose.R * v;
          bool is_held = false;
          for (const ContactFrame& f : frames)
            is_held |= (p - (face_of_b ? f.pa : f.pb)).norm() <= touch;
          if (!is_held) lowest = std::min(lowest, n.dot(p - on_plane));
        }
        return lowest - gap_offset[w];
      };
      // A floor pair's vertices each come down no faster than their own speed (the larger
      // end's, with the same margin): a domino pivoting on its edge, or lifting off it, moves
      // that edge slowly while its top sweeps round at |ω| h. A held vertex is not watched
      // (above); a sphere's lowest point moves with its centre.
      std::vector<std::vector<double>> vertex_rate(island.pairs.size());
      for (std::size_t w = 0; w < watched.size(); ++w) {
        const IslandPair& pr = island.pairs[watched[w]];
        const RigidBody& B = view.member(pr.b.index);
        if (pr.a.kind != Side::Floor || B.is_sphere() || B.is_particle()) continue;
        std::vector<double>& rate = vertex_rate[watched[w]];
        rate.assign(B.vertices().size(), 0.0);
        for (const IslandState* st : {&start, &end_n}) {
          const Vec3 v = (*st)[pr.b.index].P * B.inverse_mass();
          const Vec3 om = omega(*st, pr.b);
          const Mat3 R = rotation_of((*st)[pr.b.index], def_.rotation);
          // Or, the smaller, its speed along the floor's normal alone (as `closing_along`).
          const double turn_down = std::hypot(om.x(), om.z());
          for (std::size_t i = 0; i < rate.size(); ++i) {
            const Vec3& r = B.vertices()[i];
            rate[i] = std::max(rate[i], std::min((v + om.cross(R * r)).norm(),
                                                 std::abs(v.y()) + turn_down * r.norm()));
          }
        }
        for (double& r : rate) r = 1.25 * r + 1e-300;
      }
      auto floor_time = [&](std::size_t w, const IslandState& ns, double reach) {
        const IslandPair& pr = island.pairs[watched[w]];
        const RigidBody& B = view.member(pr.b.index);
        const std::vector<double>& rate = vertex_rate[watched[w]];
        const Pose pb = pose_of(ns[pr.b.index]);
        double soonest = INFINITY;
        for (std::size_t i = 0; i < rate.size(); ++i) {
          bool is_held = false;
          for (const IslandContact* c : held_of[watched[w]])
            is_held |= c->feature == static_cast<std::uint32_t>(i);
          if (is_held) continue;
          const double height = pb.x.y() + pb.R.row(1).dot(B.vertices()[i]) -
                                def_.floor->height - gap_offset[w];
          soonest = std::min(soonest, (std::max(height, 0.0) + reach) / rate[i]);
        }
        return soonest;
      };
      std::vector<double> free_a(watched.size());
      IslandState n_a = normalized(start, def_.rotation);
      for (std::size_t w = 0; w < watched.size(); ++w) free_a[w] = free_gap(w, n_a);
      // The stretch's motion between its two ends, for the advancement below: each member's
      // centre and orientation on the cubic Hermite curve through both ends with the rates the
      // states themselves give there (P/m, and ω from L), momenta linear. rk4's own state at
      // a time inside differs from it by the integrator's local error, O(τ⁵) (~1e-13 of a die's
      // size over a 2 ms stretch), not by the contact forces' work, which both ends carry;
      // where it is found across, the integrator's state confirms it (below). Integrating
      // from the start at every trial time cost four derivative evaluations (contact forces
      // solved in each) per trial, 60 % of ten dice's evaluations.
      // The curve starts at the stretch's start, or at the last time where the integrator's own
      // state was taken instead (below), and ends at the stretch's end.
      double curve_t0 = 0.0;
      IslandState curve_from = start;
      std::vector<Vec3> curve_omega;
      for (const Motion& m : motion[0]) curve_omega.push_back(m.omega);
      // The curve's weights at t, and member k's state there (`o` holds curve_from[k] before).
      struct Hermite {
        double th, u, h00, h10, h01, h11;
      };
      auto hermite = [&](double t) {
        const double span = remaining - curve_t0;
        const double th = (t - curve_t0) / span, u = 1.0 - th;
        return Hermite{th, u, (1.0 + 2.0 * th) * u * u, th * u * u * span,
                       th * th * (3.0 - 2.0 * th), -th * th * u * span};
      };
      auto curve_state = [&](const Hermite& hc, int k, BodyState& o) {
        const auto [th, u, h00, h10, h01, h11] = hc;
        const RigidBody& b = view.member(k);
        const BodyState& a = curve_from[k];
        const BodyState& e = end[k];
        o.x = h00 * a.x + h10 * a.P * b.inverse_mass() + h01 * e.x + h11 * e.P * b.inverse_mass();
        o.P = u * a.P + th * e.P;
        o.L = u * a.L + th * e.L;
        if (b.is_particle()) return;
        const Vec3& wa = curve_omega[static_cast<std::size_t>(k)];
        const Vec3& we = motion[1][static_cast<std::size_t>(k)].omega;
        if (def_.rotation == RotationRep::Quaternion) {
          // q̇ = ½ (0, ω) ⊗ q
          auto rate = [](const Quat& q, const Vec3& w) {
            return Vec4(-0.5 * w.dot(q.vec()), 0.5 * (q.w() * w + w.cross(q.vec())).x(),
                        0.5 * (q.w() * w + w.cross(q.vec())).y(),
                        0.5 * (q.w() * w + w.cross(q.vec())).z());
          };
          auto wxyz = [](const Quat& q) { return Vec4(q.w(), q.x(), q.y(), q.z()); };
          const Vec4 c = h00 * wxyz(a.q) + h10 * rate(a.q, wa) + h01 * wxyz(e.q) +
                         h11 * rate(e.q, we);
          o.q = Quat(c(0), c(1), c(2), c(3));
        } else {
          o.R = h00 * a.R + h10 * star(wa) * a.R + h01 * e.R + h11 * star(we) * e.R;
        }
      };
      bool curve = true;
      for (const Stepping& st : per_body) curve &= st.method == Integrator::Rk4;
      double min_span = INFINITY;
      for (std::size_t w = 0; w < watched.size(); ++w)
        min_span = std::min(min_span, pair_tol[watched[w]].toi_time_s);
      // The watched gaps at a state (with their axes and held pairs' free gaps), and which
      // pairs are across there.
      auto measure = [&](const IslandState& at, std::vector<double>& g, std::vector<Vec3>& axis,
                         std::vector<double>& free, std::vector<std::size_t>& across) {
        const IslandState ns = normalized(at, def_.rotation);
        across.clear();
        for (std::size_t w = 0; w < watched.size(); ++w) {
          g[w] = pair_gap(w, ns, &axis[w]);
          free[w] = free_gap(w, ns);
          const double noise =
              32.0 * std::numeric_limits<double>::epsilon() *
              (noise_scale + at[island.pairs[watched[w]].b.index].x.cwiseAbs().maxCoeff());
          if (g[w] < -noise) across.push_back(w);
        }
        return ns;
      };
      // Conservative advancement: no watched pair can close its gap (plus the touch distance)
      // before t + (gap + touch) / bound from a time t it was measured at; each pair is
      // measured again there, the evaluation at the soonest such time of any pair, until one is
      // found across. Measuring every pair at every evaluation instead cost a landing pile of 27
      // dice 33 000 separations a stretch, 2 in 3 of them of pairs not due for 10^4 more
      // evaluations. On the curve where it is used; the integrator's state decides a crossing
      // (below), and the stretch's end is measured whole.
      std::vector<double> g_now = gap_start, free_now = free_a;
      std::vector<Vec3> axis_now = axis_start;
      std::vector<double> seen(watched.size(), 0.0), due(watched.size(), 0.0);
      // A pair that touches at the stretch's start has no gap to advance through, and a bound
      // over its touch distance (1e-6 of its size) would cut a turning box's step into 10^4
      // pieces. Its contacts approach (resolved above) or are held by forces; what is left is a
      // new point of it going in (a corner rocking down, or swinging round on a spinning body).
      // One that goes in and stays is found at the next evaluation and bracketed; one that
      // could dip in and out between two evaluations is kept shallower than 1e-4 of the pair's
      // size (invisible) by stepping at most that far at its bound.
      auto due_after = [&](std::size_t w, double t, const IslandState& ns) {
        const Tol& tol = pair_tol[watched[w]];
        const double reach =
            pair_touching[watched[w]] ? std::max(tol.touch_m, 1e-4 * tol.length_m) : tol.touch_m;
        return t + (vertex_rate[watched[w]].empty()
                        ? std::max((std::max({g_now[w], free_now[w], 0.0}) + reach) / bound[w],
                                   (std::max(g_now[w], 0.0) + reach) /
                                       closing_along(w, axis_now[w]))
                        : floor_time(w, ns, reach));
      };
      for (std::size_t w = 0; w < watched.size(); ++w) due[w] = due_after(w, 0.0, n_a);
      // The pairs due at t (every one with `all`) measured at `at`, and the pairs touching at
      // the stretch's start and not held at every evaluation (a corner rocking down is found at
      // the first one where it is in); those found clear are due again later. A held pair is
      // measured when due only: its due time counts its free gap (its lowest vertex that is not
      // held), and its held points cannot come down inside the stretch. Measuring held pairs at
      // every evaluation was 90 % of a landing pile of 27 dice's separating-axis tests (5.1 M of
      // 5.7 M to 0.45 s, 356 evaluations a stretch). (Measured when due, the dominoes' held
      // pairs sank to the touch distance while the slack of an empty event reached pairs apart:
      // see `slack_applies`.)
      std::vector<std::size_t> crossed;
      // Which pairs are due is kept in a heap of their due times, soonest first (an entry whose
      // time is no longer its pair's is stale, and skipped), with the touching pairs not held,
      // which are measured at every evaluation. A landing heap of a hundred dice watched 317
      // pairs and measured 1.2 of them an evaluation: scanning all of them for the due ones
      // three times an evaluation (1.1 M evaluations to 0.36 s) was a tenth of its run.
      // A due time that is not a number is due at once.
      auto due_key = [&](std::size_t w) { return std::isnan(due[w]) ? -INFINITY : due[w]; };
      using DueEntry = std::pair<double, std::size_t>;
      std::priority_queue<DueEntry, std::vector<DueEntry>, std::greater<>> due_heap;
      std::vector<std::size_t> every_time;  // the touching pairs not held
      for (std::size_t w = 0; w < watched.size(); ++w)
        if (pair_touching[watched[w]] && !pair_held[watched[w]]) every_time.push_back(w);
      auto schedule_all = [&] {
        std::vector<DueEntry> entries;
        entries.reserve(watched.size());
        for (std::size_t w = 0; w < watched.size(); ++w) entries.emplace_back(due_key(w), w);
        due_heap = decltype(due_heap)(std::greater<>(), std::move(entries));
      };
      schedule_all();
      auto skip_stale = [&] {
        while (!due_heap.empty() && due_heap.top().first != due_key(due_heap.top().second))
          due_heap.pop();
      };
      // The pairs due at t, in pair order (taken off the heap: measure_due measures them all).
      std::vector<std::size_t> due_now;
      double taken_at = NAN;  // the time due_now was taken for, until it is measured
      auto take_due = [&](double t) {
        taken_at = t;
        due_now = every_time;
        for (skip_stale(); !due_heap.empty() && !(due_heap.top().first > t); skip_stale()) {
          due_now.push_back(due_heap.top().second);
          due_heap.pop();
        }
        std::sort(due_now.begin(), due_now.end());
        due_now.erase(std::unique(due_now.begin(), due_now.end()), due_now.end());
      };
      auto soonest_due = [&] {
        skip_stale();
        return due_heap.empty() ? INFINITY : due_heap.top().first;
      };
      // At the stretch's end (`at_end`: `at` is `end`) every pair's separation is known; with
      // `ready`, `at` is normalised already.
      IslandState ns_buffer;
      auto measure_due = [&](const IslandState& at, double t, bool all, bool at_end = false,
                             bool ready = false) {
        const IslandState& ns = at_end ? end_n
                                : ready ? at
                                        : (ns_buffer = normalized(at, def_.rotation));
        crossed.clear();
        if (!all && !(taken_at == t)) take_due(t);
        taken_at = NAN;
        const std::size_t count = all ? watched.size() : due_now.size();
        for (std::size_t i = 0; i < count; ++i) {
          const std::size_t w = all ? i : due_now[i];
          if (at_end) {
            g_now[w] = sep_end[w] - gap_offset[w];
            axis_now[w] = axis_end_n[w];
          } else {
            g_now[w] = pair_gap(w, ns, &axis_now[w]);
          }
          free_now[w] = free_gap(w, ns);
          const double noise =
              32.0 * std::numeric_limits<double>::epsilon() *
              (noise_scale + at[island.pairs[watched[w]].b.index].x.cwiseAbs().maxCoeff());
          if (g_now[w] < -noise) {
            crossed.push_back(w);
          } else {
            seen[w] = t;
            due[w] = due_after(w, t, ns);
            if (!all) due_heap.emplace(due_key(w), w);
          }
        }
        if (all) schedule_all();
      };
      // The last time every pair was measured clear on the integrator's own state (the
      // bracket's start where one is found across), with that state and the gaps there.
      double t_all = 0.0;
      IslandState at_all = start;
      std::vector<double> g_all = gap_start;
      double t_a = 0.0, t_b = 0.0;
      std::vector<double> g_a, g_b;
      // Between the stretch's ends on the curve, only the members of the pairs measured there
      // are put on it and normalised: the rest of `part` is stale and not read. Putting a heap
      // of a hundred dice on the curve whole at every evaluation was 38 % of its time.
      IslandState part = start;
      std::vector<char> wanted(static_cast<std::size_t>(members));
      // The pairs due at t are taken here, for the measure_due at t that follows.
      auto curve_part = [&](double t) -> const IslandState& {
        std::fill(wanted.begin(), wanted.end(), 0);
        take_due(t);
        for (std::size_t w : due_now) {
          const IslandPair& pr = island.pairs[watched[w]];
          for (const Side* side : {&pr.a, &pr.b})
            if (side->kind == Side::Member) wanted[static_cast<std::size_t>(side->index)] = 1;
        }
        const Hermite hc = hermite(t);
        for (int k = 0; k < members; ++k) {
          if (!wanted[static_cast<std::size_t>(k)]) continue;
          part[k] = curve_from[k];
          curve_state(hc, k, part[k]);
          normalize(part[k], def_.rotation);
        }
        return part;
      };
      IslandState s_b, at_lo;
      {
        bool interpolate = curve;
        constexpr int kMaxEvaluations = 10000;
        // At most kMaxEvaluations; the last one is the stretch's end, every pair measured
        // there. (Leaving the loop at the cap instead took the stretch's end unmeasured: in a
        // landing heap of a hundred dice, two dice spinning against each other at 8 m/s and
        // 3 µm apart were due every 0.35 µs, and the end they took was 1.7 mm through.)
        for (int iter = 0;; ++iter) {
          t_b = std::min(remaining, std::max(soonest_due(), t_a + 1e3 * min_span));
          if (iter == kMaxEvaluations - 1) t_b = remaining;
          const bool between = t_b < remaining;
          if (between && interpolate) {
            measure_due(curve_part(t_b), t_b, false, false, true);
          } else {
            s_b = !between ? end : advanced(t_b, nullptr);
            measure_due(s_b, t_b, !between, !between);
          }
          // Found across on the curve: the integrator's own state decides, every pair measured
          // on it. Where that is clear (a held contact the curve dipped through by its error),
          // the curve starts again from it: shorter, it errs less. Going on on the integrator
          // alone instead cost 27 dice landing in a pile 300 trials, each integrating the
          // island, after every such dip.
          if (!crossed.empty() && between && interpolate) {
            s_b = advanced(t_b, nullptr);
            measure_due(s_b, t_b, true);
            if (!crossed.empty()) {
              interpolate = false;
            } else {
              curve_t0 = t_b;
              curve_from = s_b;
              for (int k = 0; k < members; ++k)
                curve_omega[static_cast<std::size_t>(k)] = omega(s_b, Side{Side::Member, k});
              t_all = t_b, at_all = s_b, g_all = g_now;
            }
          }
          if (!crossed.empty() || !between) break;
          t_a = t_b;
        }
        // The bracket's start: the latest time each pair found across was seen clear, where
        // every pair is measured on the integrator's state. A pair across there (one that went
        // in before another was found, or that the curve passed by its error) makes that time
        // the bracket's end instead, and the search goes back to where that pair was seen clear,
        // at the latest to where every pair was.
        g_b = g_now;
        while (!crossed.empty()) {
          double lo = INFINITY;
          for (std::size_t w : crossed) lo = std::min(lo, seen[w]);
          if (!(lo > t_all && lo < t_b)) {
            t_a = t_all, at_lo = at_all, g_a = g_all;
            break;
          }
          const IslandState s_lo = advanced(lo, nullptr);
          const std::vector<std::size_t> ahead = crossed;
          measure_due(s_lo, lo, true);
          if (crossed.empty()) {
            t_a = lo, at_lo = s_lo, g_a = g_now;
            t_all = lo, at_all = s_lo, g_all = g_now;
            crossed = ahead;
            break;
          }
          t_b = lo, s_b = s_lo, g_b = g_now;
        }
      }
      if (!crossed.empty()) {
        impact = true;
        for (std::size_t w : crossed) crossed_pairs.push_back(watched[w]);
        // Regula falsi (Illinois) on the smallest gap of the pairs found across, as for the
        // floor, from [t_a, t_b] to within the finest pair's toi_time.
        // Only the members of the pairs found across are read: only they are put into
        // `gap_state` (from a state, or on the curve) and normalised; the rest is stale. (With
        // the held contacts' depths below, normalising a landing heap of a hundred dice whole
        // was 5 % of its run's time, to 0.36 s; 1 % after.)
        IslandState gap_state = start;
        auto gap_with = [&](auto&& put) {
          for (std::size_t w : crossed) {
            const IslandPair& pr = island.pairs[watched[w]];
            for (const Side* side : {&pr.a, &pr.b}) {
              if (side->kind != Side::Member) continue;
              BodyState& o = gap_state[side->index];
              put(side->index, o);
              normalize(o, def_.rotation);
            }
          }
          double g = INFINITY;
          for (std::size_t w : crossed) g = std::min(g, pair_gap(w, gap_state));
          return g;
        };
        auto gap_at = [&](const IslandState& s) {
          return gap_with([&](int k, BodyState& o) { o = s[k]; });
        };
        auto gap_on_curve = [&](double t) {
          const Hermite hc = hermite(t);
          return gap_with([&](int k, BodyState& o) {
            o = curve_from[k];
            curve_state(hc, k, o);
          });
        };
        double lo = t_a, hi = t_b;
        double g_lo = INFINITY, g_hi = INFINITY;
        for (std::size_t w : crossed) g_lo = std::min(g_lo, g_a[w]), g_hi = std::min(g_hi, g_b[w]);
        g_lo = std::max(g_lo, 0.0);
        StepInfo lo_info;
        lo_info.controller = controllers_[first];
        double toi = INFINITY;
        for (std::size_t w : crossed) toi = std::min(toi, pair_tol[watched[w]].toi_time_s);
        const double noise = 32.0 * std::numeric_limits<double>::epsilon() * noise_scale;
        const IslandState at_a = at_lo;
        const StepInfo info_a = lo_info;
        // The crossing on the curve first (it costs the gaps only), as a guess for the
        // integrator's. The curve's gap is corrected by its difference from the integrator's at
        // the bracket's ends, interpolated linearly between them, so that it brackets the
        // crossing as the integrator's does: uncorrected, a third of the crossings in a pile of
        // 27 dice were across on the integrator's state and not on the curve (1e-11–1e-9 m).
        auto locate = [&] {
          if (!curve) return locate_impact(lo, hi, g_lo, g_hi, toi, noise, at_lo, lo_info,
                                           advanced, gap_at, true);
          const double t_lo = lo, span = hi - lo;
          const double e_lo = gap_at(at_lo) - gap_on_curve(lo);
          const double e_hi = g_hi - gap_on_curve(hi);
          auto corrected = [&](double t) {
            return gap_on_curve(t) + e_lo + (e_hi - e_lo) * (t - t_lo) / span;
          };
          double clo = lo, on_curve = lo;
          int unused = 0;
          auto at = [](double t, int*) { return t; };
          locate_impact(clo, hi, std::max(corrected(lo), 0.0), corrected(hi), toi, noise, on_curve,
                        unused, at, corrected, true);
          // The gap's rate there, over 1e-3 of the bracket about it.
          const double a = std::max(lo, clo - 1e-3 * span), b = std::min(hi, clo + 1e-3 * span);
          const double slope = (corrected(b) - corrected(a)) / (b - a);
          return locate_impact_from_guess(lo, hi, g_lo, g_hi, toi, noise, at_lo, lo_info,
                                          advanced, gap_at, clo, slope, true);
        };
        bool located = locate();
        // Each trial is a step of its own from the stretch's start, so the states are not one
        // smooth path in the trial's length: where the contact forces' modes differ between
        // trials (a solve that fell back), another pair, clear at both ends of the bracket, can be
        // across where the search ends (a die's corner 1.5e-6 m into the floor in a pile of 27,
        // found at the next stretch's start as a drifted contact: 1.2e-4 J gained). Such a pair
        // joins the search, from t_a again, until it ends where no pair is across.
        for (int again = 0; again < 8; ++again) {
          std::vector<double> g_end(watched.size()), free_end(watched.size());
          std::vector<Vec3> axis_end(watched.size());
          std::vector<std::size_t> also;
          measure(at_lo, g_end, axis_end, free_end, also);
          std::erase_if(also, [&](std::size_t w) {
            return std::find(crossed.begin(), crossed.end(), w) != crossed.end();
          });
          if (also.empty()) break;
          for (std::size_t w : also) {
            crossed.push_back(w);
            crossed_pairs.push_back(watched[w]);
            toi = std::min(toi, pair_tol[watched[w]].toi_time_s);
          }
          hi = lo;
          g_hi = gap_at(at_lo);
          lo = t_a, at_lo = at_a, lo_info = info_a;
          g_lo = INFINITY;
          for (std::size_t w : crossed) g_lo = std::min(g_lo, g_a[w]);
          g_lo = std::max(g_lo, 0.0);
          located = locate();
        }
        if (!located)
          if (!diagnostics_.recur("contact_tolerance_missed"))
            diagnostics_.warn("contact_tolerance_missed", time_ + (h - remaining),
                              "the time of an impact between bodies could not be located to " +
                                  fmt("%.3g", toi) + " s",
                              "use a smaller dt (now " + fmt("%.3g", def_.dt_s) + " s)");
        tau = lo;
        end = at_lo;
        end_info = lo_info;
      }
    }
    state = end;
    for (int body : island.members) controllers_[body] = end_info.controller;
    const double t_event = time_ + (h - remaining) + tau;
    remaining = impact ? remaining - tau : 0.0;
    // Integration drift of held contacts is removed by moving the bodies apart along the
    // normal (the lighter more); it counts as penetration, its potential energy as a gain.
    // No deeper than the pair overlaps: an edge held on an edge is measured where the two
    // lines are closest, and once the edges have turned or slid so that those points are off
    // either edge, that can be far deeper than the bodies are (a die's edge 3.6e-5 m "into"
    // another that it did not overlap, in a pile of 27: pushed apart by that, and the next
    // stretch's corrections in turn, the pile gained 7e-4 J).
    //
    // A correction moves a body that other held contacts hold too: a 50 kg ball on a box on a
    // box on the floor, corrected once in pair order (the boxes', the ball's, the floor's), left
    // the boxes 2.5e-6 m into each other, the next stretch's correction the same, each stretch
    // 4 µs, and a struck pyramid's pile gained 3e-5 J so. Where a held contact is still deeper
    // than 1e-3 of the touch distance (1e-9 ℓ: far above a held point's drift in a stretch,
    // ~1e-15 ℓ) after that pass, the rest is removed by one projection of all of them together
    // (project_held_apart); sweeping the pass again converged as 0.99 a sweep under a 50:1
    // mass ratio. The penetration counted is what the stretch left, before any move; the gain,
    // that of every move.
    // `posed`: `state` normalised, moved with it (a move changes positions only).
    IslandState posed = held.empty() ? IslandState{} : normalized(state, def_.rotation);
    double correction_gain = 0.0;
    auto move = [&](const Side& side, const Vec3& by) {
      if (side.kind != Side::Member) return;
      state[side.index].x += by;
      posed[side.index].x += by;
      correction_gain -= view.member(side.index).mass() * def_.gravity.dot(by);
    };
    auto held_depth = [&](const IslandContact& c) {
      return std::min(-separation_of(c, posed),
                      -pair_separation(static_cast<std::size_t>(c.pair), posed));
    };
    for (const IslandContact& c : held) {
      const double depth = held_depth(c);
      if (!(depth > 0.0)) continue;
      const IslandPair& p = island.pairs[c.pair];
      stats_.deepest_penetration_m = std::max(stats_.deepest_penetration_m, depth);
      PairContactStats& ps = pair_stats(p.body_a, p.body_b);
      ps.deepest_penetration_m = std::max(ps.deepest_penetration_m, depth);
      if (depth > 1e-4 * pair_tol[c.pair].length_m)
        if (!diagnostics_.recur("contact_tolerance_missed"))
          diagnostics_.warn("contact_tolerance_missed", t_event,
                            "bodies resting on each other sank " + fmt("%.3g", depth) +
                                " m into each other in one step",
                            smaller_step_fix());
    }
    for (const IslandContact& c : held) {
      const double depth = held_depth(c);
      if (!(depth > 0.0)) continue;
      const IslandPair& p = island.pairs[c.pair];
      const ContactFrame f = contact_frame(view, c, state);
      const double wa = p.a.kind == Side::Member ? view.member(p.a.index).inverse_mass() : 0.0;
      const double wb = view.member(p.b.index).inverse_mass();
      move(p.b, depth * wb / (wa + wb) * f.n);
      move(p.a, -depth * wa / (wa + wb) * f.n);
    }
    bool residual = false;
    for (const IslandContact& c : held)
      residual |= held_depth(c) > 1e-3 * pair_tol[c.pair].touch_m;
    if (residual) {
      // One row per pair held: its deepest contact's depth along that contact's normal.
      std::vector<int> row_of(island.pairs.size(), -1);
      std::vector<HeldPush> rows;
      for (const IslandContact& c : held) {
        const double depth = held_depth(c);
        int& r = row_of[static_cast<std::size_t>(c.pair)];
        if (r < 0) {
          r = static_cast<int>(rows.size());
          rows.push_back({c.pair, contact_frame(view, c, state).n, depth});
        } else if (depth > rows[static_cast<std::size_t>(r)].depth) {
          rows[static_cast<std::size_t>(r)] = {c.pair, contact_frame(view, c, state).n, depth};
        }
      }
      for (const auto& [member, by] : project_held_apart(view, rows))
        move(Side{Side::Member, member}, by);
    }
    stats_.max_energy_gain_J = std::max(stats_.max_energy_gain_J, correction_gain);
    if (impact) {
      contact = true;
      const std::vector<IslandContact> now = find_contacts(state);
      // Which pairs approach, and how fast, before the impulses.
      std::vector<double> approach(island.pairs.size(), 0.0);
      for (const IslandContact& c : now)
        approach[c.pair] = std::max(approach[c.pair], -normal_speed(view, c, state));
      const bool capped = events >= budget;
      std::vector<double> impulses;
      const double rest = capped ? INFINITY : speed_scale;
      stats_.max_energy_gain_J = std::max(
          stats_.max_energy_gain_J, resolve_island_impacts(view, now, state, rest, capped, impulses));
      // An empty event: a pair found across whose touching points do not approach. Its
      // separation (the polyhedra's separating-axis value) went deeper than its points: a
      // vertex below the plane of the other's face but beyond its edges, while a tilting box
      // lifts off a face. Found across again at once, every 1e-10 s, it ran a struck pile into
      // the event cap. For the rest of the step such a pair is an impact only once it is its
      // touch distance (1e-6 of its size) deeper than a stretch starts. Not a floor pair: its
      // separation is its lowest vertex's height, no deeper than its points; one found across
      // and not approaching is a point that came down slower than it could be held, held in
      // the next stretch. With the slack, a domino that rocked back onto the floor went its
      // touch distance in unseen, and the correction gained 2.6e-9 J.
      for (std::size_t p : crossed_pairs)
        if (!(approach[p] > pair_tol[p].hold_speed_mps) && island.pairs[p].a.kind != Side::Floor)
          slack[p] = pair_tol[p].touch_m;
      // An impact is a pair that approached faster than it could be held: the other touching
      // pairs took part in the resolution at round-off speeds (1e-34 m/s on the floor).
      for (std::size_t p = 0; p < island.pairs.size(); ++p) {
        if (!(approach[p] > pair_tol[p].hold_speed_mps)) continue;
        const IslandPair& pr = island.pairs[p];
        ++stats_.impacts;
        if (stats_.events.size() < ContactStats::kMaxRecordedImpacts)
          stats_.events.push_back({t_event, pr.body_b, approach[p], pr.body_a});
        PairContactStats& ps = pair_stats(pr.body_a, pr.body_b);
        if (ps.impacts++ == 0) ps.first_impact_t_s = t_event;
      }
      if (events == budget)
        if (!diagnostics_.recur("event_cap_hit"))
          diagnostics_.warn("event_cap_hit", t_event,
                            "bodies met " + std::to_string(budget) +
                                " impacts in one step; the rest of the step was made inelastic",
                            "use a smaller dt (now " + fmt("%.3g", def_.dt_s) + " s)");
      // Pathological (a light body hammered between a heavy one and the floor): the rest of
      // the step takes every touching contact as resting (inelastic, held by contact forces)
      // and watches the touching pairs only for going the touch distance deeper, rather than
      // loop on. Each meeting of the pairs apart leaves one more pair touching; should even they
      // go on past a second budget, nothing is watched for the rest of the step.
      if (++events >= 2 * budget) settle = true;
      if (events >= 4 * budget) blind = true;
    }
    keep_step(static_cast<std::size_t>(first), end_info);
  }
  if (solve_failed && !diagnostics_.recur("contact_solve_fallback"))
    diagnostics_.warn("contact_solve_fallback", time_,
                      "the contact forces of the island of body \"" +
                          bodies_[first].name() + "\" had no exact solution the pivoting solver "
                          "reached (sliding friction); those forces were solved without the "
                          "friction of the contacts that slide",
                      smaller_step_fix());
  if (rows_cache.iterative_residual > 0.0 && !diagnostics_.recur("contact_solve_iterative"))
    diagnostics_.warn("contact_solve_iterative", time_,
                      "the contact forces of the island of body \"" + bodies_[first].name() +
                          "\" were solved iteratively (MPRGP), to a residual of " +
                          fmt("%.2g", rows_cache.iterative_residual) +
                          " of the largest free acceleration (exact: 1e-9); its contacts may "
                          "drift by that much",
                      smaller_step_fix());
  write_back();
  for (int body : island.members) {
    check_state(static_cast<std::size_t>(body));
    check_free_flight(static_cast<std::size_t>(body), contact);
  }
}

}  // namespace tumble
