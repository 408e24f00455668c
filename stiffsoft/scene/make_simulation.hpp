#pragma once
/// @file The front door: one call from a scene file, or a SceneDescription built in code, to a
/// ready Simulation, with every default resolved and every setting checked.
///
///     stiffsoft::SceneSimulation run = stiffsoft::make_simulation("scenes/default.json");
///     for (int k = 0; k < 100; ++k) run.simulation.step();

#include <filesystem>

#include <stiffsoft/coupling/model/model.hpp>
#include <stiffsoft/coupling/solver/simulation.hpp>
#include <stiffsoft/scene/element_limits.hpp>
#include <stiffsoft/scene/scene.hpp>

namespace stiffsoft {

/// A scene made ready to simulate, for callers that adjust the settings first (benchmarks):
/// the description with its relative defaults resolved, the model built from it and its
/// simulation settings (already validated).
struct PreparedScene {
  SceneDescription scene;       ///< every default filled in (the content of `scene.resolved.json`)
  Model model;                  ///< bodies, meshes, DOF layout, joints
  SimulationSettings settings;  ///< resolved (d̂, ε_v, ε_d relative to the scene's size)
};

/// A scene and the Simulation made from it.
struct SceneSimulation {
  SceneDescription scene;  ///< every default filled in, as in PreparedScene
  Simulation simulation;   ///< at t = 0, ready to step()
};

/// Loads, validates and builds a scene file (load_scene(), build_model() within `limits`), then
/// resolves its relative defaults against the model's bounding-box diagonal L: d̂ = 1e-3 L
/// (at most 1 % of the smallest body, default_dhat()),
/// ε_v = 1e-3 L/s, ε_d = 1e-2 L/s, frame_dt = max(dt, 1/60 s), and each joint's unset
/// limit_stiffness to the automatic one (docs/units.md, docs/joints.md); then, unless
/// contact.check_start_gaps is false, checks the start against d̂ (check_start_gaps()). Throws
/// SceneError naming the file and the JSON path.
PreparedScene prepare_scene(const std::filesystem::path& file, const ElementLimits& limits = {});

/// The same for a scene built in code: it is first checked against the scene schema exactly as
/// a file is (its JSON form, resolved_scene_json(), is loaded back), so errors are SceneErrors
/// naming `label` (default: "<scene.name> (built in code)") and the JSON path; a number that is
/// not finite or a string that is not valid UTF-8 is named before that (check_json_values()).
/// Mesh files must be absolute paths or relative to the working directory.
PreparedScene prepare_scene(const SceneDescription& scene, const std::string& label = {},
                            const ElementLimits& limits = {});

/// prepare_scene(file, limits), then the Simulation.
SceneSimulation make_simulation(const std::filesystem::path& file, const ElementLimits& limits = {});

/// prepare_scene(scene, label, limits), then the Simulation.
SceneSimulation make_simulation(const SceneDescription& scene, const std::string& label = {},
                                const ElementLimits& limits = {});

/// The Simulation of a prepared scene (its settings as they are now: a caller may have changed
/// them; Simulation validates them again).
SceneSimulation make_simulation(PreparedScene prepared);

}  // namespace stiffsoft
