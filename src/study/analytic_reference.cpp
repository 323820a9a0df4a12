#include "analytic_reference.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/camera.hpp"

namespace tumble::study {
namespace {

// One stretch of a body's exact motion from t0: a parabola x0 + v0 τ + ½ a τ² (a = gravity in
// flight), or resting on the floor (vertical velocity zero, sliding on frictionless at v0).
struct Phase {
  double t0 = 0.0;
  Vec3 x0, v0;
  bool resting = false;
};

struct ExactBody {
  std::vector<Phase> phases;  // by t0
  std::vector<ImpactEvent> events;
  bool rests = false;  // it comes to rest on the floor within the run
};

// Round-off and the impact times located to 1e-12 s (a vertex within 1e-10 m of the plane at
// impact speeds below 100 m/s, 1 m body): 1e-9 of the largest body is a floor no rk4 run on a
// parabola gets below, even after dozens of bounces.
constexpr double kRoundOffFloor = 1e-9;

// 2-D cross product of (b - a) and (c - a) in the floor plane (x, z).
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// True when p lies strictly inside the convex hull of `points` (monotone chain, then every hull
// edge must have p on its left by more than `margin`).
bool strictly_inside_hull(std::vector<Eigen::Vector2d> points, const Eigen::Vector2d& p,
                          double margin) {
  if (points.size() < 3) return false;
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  if (hull.size() < 3) return false;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    if (cross(a, b, p) <= margin * (b - a).norm()) return false;
  }
  return true;
}

// The lowest point of body i below its centre of mass (a particle: 0; a box does not turn).
double bottom_offset(const RigidBody& b) {
  double lowest = INFINITY;
  for (const Vec3& v : b.vertices()) lowest = std::min(lowest, (b.state.R * v).y());
  return lowest;
}

// Time from a gap `gap` >= 0 at vertical speed vy until the lowest point meets the plane,
// falling with vertical acceleration gy <= 0; none when it never comes down.
std::optional<double> time_to_floor(double gap, double vy, double gy) {
  if (gy == 0.0) {
    if (vy >= 0.0) return std::nullopt;
    return gap / -vy;
  }
  // gap + vy τ + ½ gy τ² = 0: the positive root, written without cancellation on either side.
  const double g = -gy;
  const double root = std::sqrt(vy * vy + 2.0 * g * gap);
  return vy > 0.0 ? (vy + root) / g : 2.0 * gap / (root - vy);
}

ExactBody exact_body(const StudySetup& setup, std::size_t index) {
  const RigidBody& b = setup.bodies[index];
  const WorldDef& def = setup.def;
  const Vec3& g = def.gravity;
  const double t_end = setup.times.empty() ? 0.0 : setup.times.back();
  ExactBody out;
  Phase phase{0.0, b.state.x, b.velocity(), false};
  if (!def.floor) {
    out.phases.push_back(phase);
    return out;
  }
  const ContactTolerances& tol = setup.tolerances[index];
  // The rest speed of the small-dt limit: for_body(ℓ, g, dt → 0).
  const ContactTolerances limit = ContactTolerances::for_body(tol.length_m, g, 0.0);
  const double floor_y = def.floor->height, offset = bottom_offset(b);
  const double e = b.restitution();
  auto settle = [&](Phase p) {
    // Held on the floor: vertical velocity zero (an inelastic impact); a box on a face whose
    // points are all slower than the sleep speed is put at rest (P = L = 0), as the World does.
    p.resting = true;
    out.rests = p.t0 <= t_end;
    p.v0.y() = 0.0;
    p.x0.y() = floor_y - offset;
    if (!b.is_particle() && p.v0.norm() < limit.sleep_speed_mps) p.v0.setZero();
    out.phases.push_back(p);
  };
  // Starting on the floor, not separating faster than the hold speed nor approaching faster than
  // the rest speed: resting from t = 0, without an impact (as the World's resting set).
  const double gap0 = phase.x0.y() + offset - floor_y;
  if (gap0 <= tol.touch_m && phase.v0.y() <= limit.hold_speed_mps &&
      phase.v0.y() >= -limit.rest_speed_mps) {
    settle(phase);
    return out;
  }
  for (;;) {
    out.phases.push_back(phase);
    const double gap = std::max(phase.x0.y() + offset - floor_y, 0.0);
    const std::optional<double> tau = time_to_floor(gap, phase.v0.y(), g.y());
    if (!tau || phase.t0 + *tau > t_end) return out;
    Phase next;
    next.t0 = phase.t0 + *tau;
    next.x0 = phase.x0 + phase.v0 * *tau + 0.5 * g * (*tau * *tau);
    next.x0.y() = floor_y - offset;  // exactly on the plane
    // The approach speed from energy, exact where v + g τ would lose digits near the apex.
    const double speed = std::sqrt(phase.v0.y() * phase.v0.y() + 2.0 * -g.y() * gap);
    next.v0 = phase.v0 + g * *tau;
    out.events.push_back({next.t0, static_cast<int>(index), speed});
    // Newton's law with the model's cut-off: at or below the rest speed the impact is inelastic.
    if (speed <= limit.rest_speed_mps || e * speed <= limit.hold_speed_mps) {
      settle(next);
      return out;
    }
    next.v0.y() = e * speed;
    phase = next;
  }
}

BodyState state_at(const RigidBody& b, const ExactBody& motion, const Vec3& g, double t) {
  auto it = std::upper_bound(motion.phases.begin(), motion.phases.end(), t,
                             [](double time, const Phase& p) { return time < p.t0; });
  const Phase& p = it == motion.phases.begin() ? motion.phases.front() : *(it - 1);
  const double tau = t - p.t0;
  BodyState s = b.state;  // orientation and L = 0 never change
  Vec3 v = p.v0;
  if (p.resting) {
    s.x = p.x0 + p.v0 * tau;
  } else {
    s.x = p.x0 + p.v0 * tau + 0.5 * g * (tau * tau);
    v += g * tau;
  }
  s.P = b.mass() * v;
  return s;
}

}  // namespace

std::optional<std::string> analytic_obstacle(const StudySetup& setup) {
  const WorldDef& def = setup.def;
  if (def.linear_drag != 0.0 || def.angular_drag != 0.0) return "the scene models drag";
  const Vec3& g = def.gravity;
  if (def.floor) {
    if (g.x() != 0.0 || g.z() != 0.0) return "gravity is not perpendicular to the floor";
    if (g.y() > 0.0) return "gravity points away from the floor";
  }
  if (def.collisions)
    for (std::size_t i = 0; i < setup.bodies.size(); ++i)
      for (std::size_t j = i + 1; j < setup.bodies.size(); ++j)
        if (!setup.bodies[i].is_particle() || !setup.bodies[j].is_particle())
          return "its bodies may meet each other";
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    const RigidBody& b = setup.bodies[i];
    const std::string name = "body \"" + b.name() + "\"";
    if (b.is_sphere()) return name + " is a sphere (it may roll)";
    if (b.is_fixed()) return name + " is fixed";
    if (!b.is_particle() && b.state.L != Vec3::Zero()) return name + " spins";
    if (!def.floor) continue;
    const Vec3 v = b.velocity();
    if (def.floor->friction > 0.0 && (v.x() != 0.0 || v.z() != 0.0))
      return name + " slides on a floor with friction";
    if (b.is_particle()) continue;
    // A flat face down: the lowest vertices level within the touch tolerance, at least 3 of them,
    // the centre of mass strictly above their hull (else the landing would tip it).
    const double lowest = bottom_offset(b);
    std::vector<Eigen::Vector2d> face;
    for (const Vec3& vertex : b.vertices()) {
      const Vec3 r = b.state.R * vertex;
      if (r.y() - lowest <= setup.tolerances[i].touch_m) face.emplace_back(r.x(), r.z());
    }
    if (face.size() < 3 ||
        !strictly_inside_hull(face, Eigen::Vector2d::Zero(), setup.tolerances[i].touch_m))
      return name + " does not land on a flat face";
  }
  return std::nullopt;
}

AnalyticReference analytic_reference(const StudySetup& setup) {
  AnalyticReference out;
  RunRecord& record = out.record;
  for (const ContactTolerances& t : setup.tolerances)
    out.uncertainty_m = std::max(out.uncertainty_m, kRoundOffFloor * t.length_m);
  record.times = setup.times;
  std::vector<ExactBody> motion;
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    motion.push_back(exact_body(setup, i));
    const ContactTolerances limit =
        ContactTolerances::for_body(setup.tolerances[i].length_m, setup.def.gravity, 0.0);
    record.rest_speed_mps.push_back(limit.rest_speed_mps);
    if (motion.back().rests)
      out.uncertainty_m = std::max(out.uncertainty_m, setup.tolerances[i].touch_m);
    for (const ImpactEvent& e : motion.back().events) record.events.push_back(e);
  }
  std::stable_sort(record.events.begin(), record.events.end(),
                   [](const ImpactEvent& a, const ImpactEvent& b) { return a.t_s < b.t_s; });
  const std::optional<std::size_t> followed = followed_body(*setup.scene);
  for (const double t : setup.times) {
    std::vector<BodyState> states;
    for (std::size_t i = 0; i < setup.bodies.size(); ++i)
      states.push_back(state_at(setup.bodies[i], motion[i], setup.def.gravity, t));
    const Vec3 target = followed ? states[*followed].x : setup.scene->camera.target;
    const Eigen::Matrix4d vp = camera_view_projection(*setup.scene, target);
    std::vector<BodySample>& row = record.samples.emplace_back();
    for (std::size_t i = 0; i < states.size(); ++i)
      row.push_back(sample_body(setup, i, states[i], vp));
  }
  return out;
}

}  // namespace tumble::study
