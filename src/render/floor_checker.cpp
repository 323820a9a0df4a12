// The floor checker's scale: squares of a power of ten near the moving bodies' size.
#include <algorithm>
#include <cmath>

#include "tumble/camera.hpp"
#include "tumble/renderer.hpp"

namespace tumble {

double checker_tile_m(const Scene& scene, const SceneModels* models) {
  double largest = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    // A fixed ramp or table is the stage, not the subject; a particle's size is a marker.
    if (b.fixed || b.shape == Shape::Particle) continue;
    double extent = b.size.maxCoeff();  // box: edges; sphere: 2r
    if (b.shape == Shape::Mesh) {
      const MeshBody* model = models != nullptr ? models->model(i) : nullptr;
      if (model == nullptr || model->mesh.vertices.empty()) continue;
      Vec3 lo = model->mesh.vertices.front(), hi = lo;
      for (const Vec3& p : model->mesh.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      extent = (hi - lo).maxCoeff();
    }
    if (std::isfinite(extent) && extent > 0.0) largest = std::max(largest, extent);
  }
  if (!(largest > 0.0)) return 1.0;
  // Nearest in log scale: 0.3-3 m gives 1 m (the default scene's 1 m box keeps its 1 m squares).
  // The exponent is clamped to where a float32 world coordinate still resolves a square.
  const double exponent = std::clamp(std::round(std::log10(largest)), -6.0, 6.0);
  return std::pow(10.0, exponent);
}

double floor_tile_m(const Scene& scene, const SceneModels* models) {
  double tile = checker_tile_m(scene, models);
  if (!scene.floor) return tile;
  const Eigen::Matrix4d view_projection = camera_view_projection(scene, scene.camera.target);
  const Vec3 below(scene.camera.target.x(), scene.floor->height, scene.camera.target.z());
  const int w = scene.render.width, h = scene.render.height;
  // A square's sides on screen at the point below the target: its shortest is what aliases.
  const auto shortest_side_px = [&](double side) {
    const auto o = to_pixels(view_projection, below, w, h);
    const auto x = to_pixels(view_projection, below + Vec3(side, 0.0, 0.0), w, h);
    const auto z = to_pixels(view_projection, below + Vec3(0.0, 0.0, side), w, h);
    if (!o || !x || !z) return double(INFINITY);  // behind the camera: nothing to measure
    return std::min((*x - *o).norm(), (*z - *o).norm());
  };
  constexpr double kMinSquarePx = 4.0;
  for (int k = 0; k < 3 && shortest_side_px(tile) < kMinSquarePx; ++k) tile *= 10.0;
  return tile;
}

}  // namespace tumble
