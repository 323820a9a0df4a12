#pragma once
/// A camera that frames the whole run. When a scene states no camera position (and no target),
/// tumble simulates the run first (cheap next to drawing it), takes every point the bodies
/// occupy at every frame time, and places the camera looking from the direction of (5, 3, 6) at
/// the centre of all of it, at the distance where every point fits the image with a margin
/// (perspective: through the field of view; orthographic: the ortho height is chosen too,
/// unless the scene gives it). A stated position or target is kept as given:
///   - neither stated: target = the centre of the run's extent, position framed;
///   - target only: the target kept, position framed along the default direction;
///   - position (with or without target): the scene's camera as it is (its target, or the
///     default target), nothing framed.
/// camera.follow with a stated position: the camera stays there and turns towards the body at
/// every frame. camera.follow without one: the run is not framed; the camera looks at the body
/// from the direction of (5, 3, 6), close enough for the body's bounding sphere to span
/// kFollowShare of the image's height (and width), and moves with it (camera.hpp,
/// camera_moves_with_target), so a thrown body stays as large as it starts. No GL here:
/// `tumble render` and `tumble study` frame alike.

#include <span>

#include "tumble/scene.hpp"
#include "tumble/world.hpp"

namespace tumble {

/// Share of the image's half-width and half-height left empty around the framed points.
inline constexpr double kFramingMargin = 0.1;

/// Share of the image's height (or width, if narrower) a followed body's bounding sphere spans:
/// a box then shows at least 0.4 / sqrt(3) = 23 % of the height whichever way it turns (its
/// thinnest silhouette is an edge length, a sqrt(3)-th of its bounding diameter).
inline constexpr double kFollowShare = 0.4;

/// The camera fitted to `points` (world) in an image of `aspect` (width / height): target at
/// the centre of their bounding box when `fit_target`, else camera.target; position along
/// kFramingDirection at the smallest distance where every point is inside the image with the
/// margin, and in front of the near plane; ortho height fitted when `fit_ortho_height`. Up,
/// field of view, projection and follow are kept. `points` must not be empty.
CameraSettings fit_camera(const CameraSettings& camera, std::span<const Vec3> points, double aspect,
                          bool fit_target, bool fit_ortho_height);

/// The camera following a body whose bounding sphere has `radius_m` and whose centre is at
/// `centre` now: target = centre, position along kFramingDirection at the distance where the
/// sphere spans kFollowShare of the image (and at least two radii away); ortho height fitted the
/// same way when `fit_ortho_height`. Up, field of view, projection and follow are kept.
CameraSettings follow_camera(const CameraSettings& camera, const Vec3& centre, double radius_m,
                             double aspect, bool fit_ortho_height);

/// The radius of the sphere about body `i`'s centre of mass that holds it as drawn, whatever
/// its orientation: a box's or mesh hull's farthest vertex, a sphere's or particle's radius.
double bounding_radius(const Scene& scene, const World& world, std::size_t i);

/// Every point the bodies of `world` occupy, as drawn: a box's corners, a mesh's hull vertices,
/// a particle's drawn sphere (its bounding box). Appended to `points`.
void body_points(const Scene& scene, const World& world, std::vector<Vec3>& points);

/// The camera `tumble render` and `tumble study` use for `scene`: as stated; following the body
/// camera.follow names (follow_camera at t = 0, `framed` set); or framed on the run of `def`
/// (scene.camera with `framed` set) sampled at every frame time k / fps and at the end (a run
/// that stops being finite: up to there). Deterministic: a pure function of the
/// scene (the run is simulated afresh).
CameraSettings frame_camera(const Scene& scene, const WorldDef& def);

}  // namespace tumble
