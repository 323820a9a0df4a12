#pragma once
/// Turns a validated Scene into the plain WorldDef the simulation layer runs: mass from density,
/// principal moments, contact vertices, restitution inherited from the floor. Checks what only
/// the assembled bodies can show (a body starting inside the floor) and reports it against the
/// body's place in the scene file.

#include "tumble/scene.hpp"
#include "tumble/world.hpp"

namespace tumble {

/// Throws tumble::Error (BadInput) when a body starts below the floor.
WorldDef make_world_def(const Scene& scene);

}  // namespace tumble
