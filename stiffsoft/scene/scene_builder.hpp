#pragma once
/// @file From a loaded scene to what the simulator runs: the Model (meshes, mass properties,
/// initial configurations). The front door (make_simulation.hpp) turns the rest of a scene into
/// resolved SimulationSettings.

#include <filesystem>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/scene/element_limits.hpp>
#include <stiffsoft/scene/scene.hpp>

namespace stiffsoft {

/// Builds the model: reads or makes every body's surface, checks it closed, manifold and
/// outward-oriented; decides `auto` bodies (model_choice.hpp); affine bodies get exact mass
/// properties (divergence theorem), soft bodies a gmsh tet mesh (cached), lumped masses and
/// their Dirichlet conditions; places them and checks that no two bodies overlap (exact
/// predicates). Before any primitive is made or body tet-meshed, its triangle count and expected
/// tet count are checked against `limits` (element_limits.hpp). Errors are SceneError naming
/// `file`, the body's JSON path and, for overlaps, both bodies.
Model build_model(const SceneDescription& scene, const std::filesystem::path& file, const ElementLimits& limits = {});

/// The body's model for output: "soft", or for affine bodies "affine", "fixed", "kinematic".
const char* motion_name(const BodyModel& body);

}  // namespace stiffsoft
