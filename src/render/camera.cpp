#include "tumble/camera.hpp"

#include <algorithm>
#include <cmath>

namespace tumble {

using Mat4 = Eigen::Matrix4d;

Mat4 look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
  const Vec3 f = (target - eye).normalized();
  const Vec3 s = f.cross(up).normalized();
  const Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Mat4 perspective(double fov_y_deg, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(0.5 * radians(fov_y_deg));
  Mat4 m = Mat4::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2.0 * far * near / (near - far);
  m(3, 2) = -1.0;
  return m;
}

Mat4 orthographic(double height, double aspect, double near, double far) {
  Mat4 m = Mat4::Identity();
  m(0, 0) = 2.0 / (height * aspect);
  m(1, 1) = 2.0 / height;
  m(2, 2) = -2.0 / (far - near);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

std::optional<std::size_t> followed_body(const Scene& scene) {
  if (!scene.camera.follow) return std::nullopt;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (scene.bodies[i].name == *scene.camera.follow) return i;
  return std::nullopt;
}

Vec3 camera_target(const Scene& scene, const World& world) {
  const std::optional<std::size_t> i = followed_body(scene);
  return i && *i < world.bodies().size() ? world.bodies()[*i].state.x : scene.camera.target;
}

bool camera_moves_with_target(const CameraSettings& camera) {
  return camera.follow && !camera.position_given;
}

Vec3 camera_eye(const Scene& scene, const Vec3& target) {
  const CameraSettings& cam = scene.camera;
  return camera_moves_with_target(cam) ? Vec3(target + (cam.position - cam.target)) : cam.position;
}

Vec3 camera_eye(const Scene& scene, const World& world) {
  return camera_eye(scene, camera_target(scene, world));
}

Mat4 camera_view_projection(const Scene& scene, const Vec3& target) {
  const CameraSettings& cam = scene.camera;
  const Vec3 eye = camera_eye(scene, target);
  const Mat4 view = look_at(eye, target, cam.up);
  // Depth range from the camera's distance to the scene: a near plane too close wastes depth
  // precision, too far clips the bodies.
  const double distance = (eye - target).norm();
  const double near = std::max(0.01, 0.02 * distance), far = 200.0 + 4.0 * distance;
  const double aspect = double(scene.render.width) / scene.render.height;
  // The same eye, view axis and depth range in both projections: an orthographic camera differs
  // only in its parallel rays, so switching projection keeps the framing's centre and the
  // light, shading and depth order of the picture. (A near plane > 0 still clips what is
  // behind the eye, as a perspective camera would.)
  if (cam.projection == Projection::Orthographic)
    return orthographic(cam.ortho_height_m, aspect, near, far) * view;
  return perspective(cam.fov_deg, aspect, near, far) * view;
}

Mat4 camera_view_projection(const Scene& scene, const World& world) {
  return camera_view_projection(scene, camera_target(scene, world));
}

std::optional<Eigen::Vector2d> to_pixels(const Mat4& view_projection, const Vec3& point, int width,
                                         int height) {
  const Eigen::Vector4d clip = view_projection * point.homogeneous();
  // The renderer's own test for "behind the camera" (its FXAA rectangles use the same bound).
  if (clip.w() <= 1e-6) return std::nullopt;
  const double ndc_x = clip.x() / clip.w(), ndc_y = clip.y() / clip.w();
  // NDC y points up, image rows go down.
  return Eigen::Vector2d((ndc_x + 1.0) * 0.5 * width, (1.0 - ndc_y) * 0.5 * height);
}

}  // namespace tumble
