#pragma once
/// @file From a loaded scene to what the simulator runs: the Model (meshes, mass properties,
/// initial configurations) and resolved SimulationSettings.

#include <filesystem>
#include <vector>

#include "coupling/model.hpp"
#include "coupling/simulation.hpp"
#include "io/scene.hpp"

namespace stiffsoft {

/// Builds the model: reads or makes every body's surface, checks it closed, manifold and
/// outward-oriented; decides `auto` bodies (model_choice.hpp); affine bodies get exact mass
/// properties (divergence theorem), soft bodies a gmsh tet mesh (cached), lumped masses and
/// their Dirichlet conditions; places them and checks that no two bodies overlap (exact
/// predicates). Errors are SceneError naming `file`, the body's JSON path and, for overlaps,
/// both bodies.
Model build_model(const SceneDescription& scene, const std::filesystem::path& file);

/// Fills the scene's relative defaults (d̂, ε_v, Newton tolerance, frame interval) from the
/// model's bounding-box diagonal L: d̂ = 1e-3 L, ε_v = 1e-3 L/s, ε_d = 1e-2 L/s,
/// frame_dt = max(dt, 1/60 s); and each joint's unset limit_stiffness from the model's
/// (automatic: m_a (|g| ℓ_a + ½ v_a²), docs/joints.md), so the resolved scene shows it.
void resolve_relative_defaults(SceneDescription& scene, const Model& model);

/// Simulation settings of a scene whose relative defaults are resolved.
SimulationSettings simulation_settings(const SceneDescription& scene);

/// The body's model for output: "soft", or for affine bodies "affine", "fixed", "kinematic".
const char* motion_name(const BodyModel& body);

}  // namespace stiffsoft
