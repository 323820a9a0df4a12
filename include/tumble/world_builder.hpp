#pragma once
/// Turns a validated Scene into the plain WorldDef the simulation layer runs: mass from density,
/// principal moments, contact vertices, restitution inherited from the floor. Checks what only
/// the assembled bodies can show (a body starting inside the floor) and reports it against the
/// body's place in the scene file. Mesh bodies are loaded once (SceneModels) and shared by the
/// world (mass properties, hull vertices) and the renderer (triangles).

#include <memory>
#include <optional>
#include <vector>

#include "tumble/mesh.hpp"
#include "tumble/scene.hpp"
#include "tumble/world.hpp"

namespace tumble {

/// The loaded model of each body, in scene order (empty for boxes and particles). A scene
/// without meshes loads nothing.
struct SceneModels {
  std::vector<std::shared_ptr<const MeshBody>> bodies;
  /// The model of body i, or null when it has none.
  const MeshBody* model(std::size_t i) const {
    return i < bodies.size() ? bodies[i].get() : nullptr;
  }
};

/// Loads every body's mesh. Throws tumble::Error (BadInput) naming the mesh file and the problem.
SceneModels load_models(const Scene& scene);

/// The largest step of an adaptive run: the scene's max_step, else `sample_interval_s` (the
/// interval between the samples the run takes), so that every sample falls on a step boundary.
double adaptive_max_step_s(const SimulationSettings& sim, double sample_interval_s);

/// Throws tumble::Error (BadInput) when a body starts below the floor. For `adaptive`, the
/// WorldDef's dt is its largest step (adaptive_max_step_s over `sample_interval_s`, default the
/// frame interval 1/fps) and the scene's dt its first trial step; the fixed-step integrators step
/// at the scene's dt.
WorldDef make_world_def(const Scene& scene, const SceneModels& models,
                        std::optional<double> sample_interval_s = std::nullopt);
/// The same, loading the models itself.
WorldDef make_world_def(const Scene& scene);

}  // namespace tumble
