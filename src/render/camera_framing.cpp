#include "tumble/camera_framing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>

#include "tumble/camera.hpp"
#include "tumble/error.hpp"
#include "tumble/sampler.hpp"

namespace tumble {

CameraSettings fit_camera(const CameraSettings& camera, std::span<const Vec3> points, double aspect,
                          bool fit_target, bool fit_ortho_height) {
  assert(!points.empty() && aspect > 0.0);
  CameraSettings c = camera;
  if (fit_target) {
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    c.target = 0.5 * (lo + hi);
  }
  // The view basis look_at() builds for a camera on the ray target + D·d: forward f = -d,
  // right s = f × up, up' = s × f. A point r from the target is x = r·s across, y = r·up' up,
  // and at depth D - r·d in front of the eye.
  const Vec3 d = kFramingDirection.normalized();
  const Vec3 f = -d;
  const Vec3 s = f.cross(c.up).normalized();
  const Vec3 u = s.cross(f);
  const double tan_y = std::tan(0.5 * radians(c.fov_deg)) * (1.0 - kFramingMargin);
  const double tan_x = tan_y * aspect;
  double distance = 0.0, half_x = 0.0, half_y = 0.0, nearest = -INFINITY;
  for (const Vec3& p : points) {
    const Vec3 r = p - c.target;
    const double x = std::abs(r.dot(s)), y = std::abs(r.dot(u)), z = r.dot(d);
    // Perspective: |x| <= tan_x (D - z) and |y| <= tan_y (D - z), so D >= z + |x| / tan_x...
    distance = std::max({distance, z + x / tan_x, z + y / tan_y});
    half_x = std::max(half_x, x);
    half_y = std::max(half_y, y);
    nearest = std::max(nearest, z);
  }
  // In front of the near plane (camera.cpp: max(0.01, 0.02 D)) with room to spare: D - z must
  // exceed 0.02 D, so D > z / 0.98; 5 % more, and never closer than 1 cm plus that.
  distance = std::max(distance, 1.05 * (std::max(nearest, 0.0) + 0.01) / 0.98);
  // An orthographic camera stands where the perspective one would (its eye only sets the
  // depth range); its height shows every point with the same margin.
  if (c.projection == Projection::Orthographic && fit_ortho_height) {
    const double height = 2.0 * std::max(half_y, half_x / aspect) / (1.0 - kFramingMargin);
    if (height > 0.0) c.ortho_height_m = height;
  }
  c.position = c.target + distance * d;
  c.framed = true;
  return c;
}

CameraSettings follow_camera(const CameraSettings& camera, const Vec3& centre, double radius_m,
                             double aspect, bool fit_ortho_height) {
  assert(radius_m > 0.0 && aspect > 0.0);
  CameraSettings c = camera;
  c.target = centre;
  // The sphere's diameter 2r seen at distance D spans 2r / (2 D tan(fov/2)) of the height
  // (nearly: its silhouette is a little wider, 1 / sqrt(1 - (r/D)^2), 3 % at the default fov).
  const double share = kFollowShare * std::min(1.0, aspect);
  const double tan_y = std::tan(0.5 * radians(c.fov_deg));
  // Two radii at least: a very wide field of view must not put the eye inside the body.
  const double distance = std::max(radius_m / (share * tan_y), 2.0 * radius_m);
  if (c.projection == Projection::Orthographic && fit_ortho_height)
    c.ortho_height_m = 2.0 * radius_m / share;
  c.position = c.target + distance * kFramingDirection.normalized();
  c.framed = true;
  return c;
}

double bounding_radius(const Scene& scene, const World& world, std::size_t i) {
  const RigidBody& b = world.bodies()[i];
  // Drawn as a sphere of diameter `size` (body_points).
  if (b.is_particle() || b.is_sphere()) return 0.5 * scene.bodies[i].size.maxCoeff();
  double r = 0.0;
  for (const Vec3& v : b.vertices()) r = std::max(r, v.norm());  // about the centre of mass
  return r;
}

void body_points(const Scene& scene, const World& world, std::vector<Vec3>& points) {
  const std::vector<RigidBody>& bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    if (b.is_particle() || b.is_sphere()) {
      // Drawn as a sphere of diameter `size` (per axis): the corners of its bounding box.
      const Vec3 half = 0.5 * scene.bodies[i].size;
      for (int k = 0; k < 8; ++k)
        points.push_back(b.state.x + Vec3((k & 1) ? half.x() : -half.x(),
                                          (k & 2) ? half.y() : -half.y(),
                                          (k & 4) ? half.z() : -half.z()));
      continue;
    }
    // Box corners and mesh hull vertices, in the principal frame: the drawn model is inside.
    for (const Vec3& v : b.vertices()) points.push_back(b.state.x + b.state.R * v);
  }
}

CameraSettings frame_camera(const Scene& scene, const WorldDef& def) {
  const CameraSettings& stated = scene.camera;
  if (stated.position_given) return stated;
  const double aspect = double(scene.render.width) / scene.render.height;
  if (const std::optional<std::size_t> i = followed_body(scene)) {
    // A followed body is framed alone, and the camera moves with it: no run to look at.
    const World start(def);
    const double radius = bounding_radius(scene, start, *i);
    if (radius > 0.0)
      return follow_camera(stated, start.bodies()[*i].state.x, radius, aspect,
                           !stated.ortho_height_given);
  }
  World world(def);
  Sampler sampler(world);
  std::vector<Vec3> points;
  const int fps = scene.render.fps;
  const double duration = scene.simulation.duration_s;
  const long frames = std::lround(duration * fps);
  try {
    for (long k = 0; k < frames; ++k) body_points(scene, sampler.at(double(k) / fps), points);
    body_points(scene, sampler.at(duration), points);
  } catch (const Error&) {
    // The run stops being finite: framed on what came before (t = 0 at least). `render` meets
    // the same error when it runs and exits with it; `study` keeps the run as a diverged row.
    if (points.empty()) throw;
  }
  return fit_camera(stated, points, aspect, !stated.target_given, !stated.ortho_height_given);
}

}  // namespace tumble
