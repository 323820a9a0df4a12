#pragma once
/// Camera maths without GL: the view and projection matrices the renderer draws with, and where a
/// world point lands in the image. `tumble study` measures screen-space error with these, so a
/// pixel there is a pixel of the rendered clip.

#include <optional>

#include "tumble/math.hpp"
#include "tumble/scene.hpp"
#include "tumble/world.hpp"

namespace tumble {

/// View matrix of a camera at `eye` looking at `target` (right-handed, OpenGL conventions).
Eigen::Matrix4d look_at(const Vec3& eye, const Vec3& target, const Vec3& up);
/// OpenGL perspective projection (clip space, depth to [-1, 1]).
Eigen::Matrix4d perspective(double fov_y_deg, double aspect, double near, double far);
/// OpenGL orthographic projection of a view `height` units tall (width = height · aspect),
/// centred on the view axis, depth [near, far] to [-1, 1]. Clip w is 1 for every point.
Eigen::Matrix4d orthographic(double height, double aspect, double near, double far);

/// Index (scene order) of the body `camera.follow` names, if any.
std::optional<std::size_t> followed_body(const Scene& scene);
/// The point the scene's camera looks at when the bodies are as in `world`: the followed body's
/// centre of mass, or camera.target.
Vec3 camera_target(const Scene& scene, const World& world);
/// Whether the camera moves with the body it follows: camera.follow without a stated position.
/// It then keeps the offset position − target (camera_framing.hpp places it close enough for
/// the body to fill a share of the picture); with a stated position it stays there and turns.
bool camera_moves_with_target(const CameraSettings& camera);
/// Where the scene's camera is when it looks at `target`: camera.position, or for a camera that
/// moves with its body, target + (position − camera.target).
Vec3 camera_eye(const Scene& scene, const Vec3& target);
/// Where the scene's camera is for the bodies as they are in `world`.
Vec3 camera_eye(const Scene& scene, const World& world);
/// View-projection of the scene's camera looking at `target` from camera_eye(), at the scene's
/// image aspect, in its projection (perspective with fov_deg, or orthographic ortho_height_m
/// tall). The depth range follows the camera's distance to the target.
Eigen::Matrix4d camera_view_projection(const Scene& scene, const Vec3& target);
/// View-projection of the scene's camera for the bodies as they are in `world` (camera.follow
/// included): what Renderer::draw() draws with.
Eigen::Matrix4d camera_view_projection(const Scene& scene, const World& world);

/// Where `point` (world) lands in a `width` × `height` image seen through `view_projection`:
/// pixels from the top-left corner (x right, y down; pixel centres at half-integers). Points
/// outside the image are still returned; nullopt when the point is behind the camera.
std::optional<Eigen::Vector2d> to_pixels(const Eigen::Matrix4d& view_projection, const Vec3& point,
                                         int width, int height);

}  // namespace tumble
