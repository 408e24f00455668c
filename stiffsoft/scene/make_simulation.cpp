#include <stiffsoft/scene/make_simulation.hpp>

#include <algorithm>
#include <stdexcept>

#include <stiffsoft/scene/scene_builder.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <stiffsoft/scene/scene_text.hpp>
#include <stiffsoft/scene/start_gaps.hpp>

namespace stiffsoft {

namespace {

/// Fills the scene's relative defaults (see prepare_scene()) from the model.
void resolve_relative_defaults(SceneDescription& scene, const Model& model) {
  const double L = model.bounding_box_diagonal();
  if (!scene.contact.dhat) scene.contact.dhat = default_dhat(model);
  if (!scene.contact.eps_v) scene.contact.eps_v = 1e-3 * L;
  if (!scene.solver.tolerance) scene.solver.tolerance = 1e-2 * L;
  if (!scene.solver.sleep_speed) scene.solver.sleep_speed = scene.solver.tolerance;
  if (!scene.output.frame_dt) scene.output.frame_dt = std::max(scene.time.dt, 1.0 / 60.0);
  for (std::size_t j = 0; j < scene.joints.size() && j < model.joints.size(); ++j)
    if (!scene.joints[j].limit_stiffness) scene.joints[j].limit_stiffness = model.joints[j].limit_stiffness;
}

/// Simulation settings of a scene whose relative defaults are resolved.
SimulationSettings simulation_settings(const SceneDescription& scene, const std::string& label) {
  SimulationSettings s;
  s.h = scene.time.dt;
  s.integrator = scene.time.integrator;
  s.gravity = scene.gravity;
  s.dhat = scene.contact.dhat.value();
  s.mu = scene.contact.mu;
  s.eps_v = scene.contact.eps_v.value();
  s.kappa = scene.contact.kappa;
  s.contact_damping = scene.contact.damping;
  for (std::size_t k = 0; k < scene.contact.pairs.size(); ++k) {
    const ContactPairDescription& pair = scene.contact.pairs[k];
    const auto index = [&](const std::string& name, const char* key) {
      for (std::size_t i = 0; i < scene.bodies.size(); ++i)
        if (scene.bodies[i].name == name) return int(i);
      throw SceneError(label, "contact.pairs[" + std::to_string(k) + "]." + key,
                       "no body is named \"" + name + "\"");
    };
    s.contact_pair_damping.push_back({index(pair.body_a, "body_a"), index(pair.body_b, "body_b"), pair.damping});
  }
  s.balance_kappa = scene.contact.balance_kappa;
  s.friction_iterations = scene.contact.friction_iterations;
  s.tolerance = scene.solver.tolerance.value();
  s.gap_tolerance = scene.solver.gap_tolerance;
  s.max_iterations = scene.solver.max_iterations;
  s.barrier_hessian = scene.solver.barrier_hessian;
  s.release_hessian = scene.solver.release_hessian;
  s.geodesic_line_search = scene.solver.geodesic_line_search;
  s.island_line_search = scene.solver.island_line_search;
  s.entering_springs = scene.solver.entering_springs;
  s.linear_solver = scene.solver.linear;
  s.krylov_rtol_max = scene.solver.krylov_rtol_max;
  s.rigidity_bound = scene.solver.rigidity_bound;
  s.sleep_time = scene.solver.sleep_time;
  s.sleep_speed = scene.solver.sleep_speed;
  validate(s);
  return s;
}

/// The model and settings of a scene already checked against the schema.
PreparedScene prepare_checked(SceneDescription scene, const std::filesystem::path& file, const ElementLimits& limits) {
  Model model = build_model(scene, file, limits);
  const bool dhat_given = scene.contact.dhat.has_value();
  resolve_relative_defaults(scene, model);
  if (scene.contact.check_start_gaps) check_start_gaps(model, scene.contact.dhat.value(), dhat_given, file.string());
  SimulationSettings settings = simulation_settings(scene, file.string());
  return {std::move(scene), std::move(model), std::move(settings)};
}

}  // namespace

PreparedScene prepare_scene(const std::filesystem::path& file, const ElementLimits& limits) {
  return prepare_checked(load_scene(file), file, limits);
}

PreparedScene prepare_scene(const SceneDescription& scene, const std::string& label, const ElementLimits& limits) {
  const std::string file = label.empty() ? scene.name + " (built in code)" : label;
  const nlohmann::ordered_json json = resolved_scene_json(scene);
  check_json_values(json, file);  // NaN and invalid UTF-8 cannot pass through text
  SceneDescription checked = load_scene_from_string(json.dump(), std::filesystem::current_path(), file, scene.name);
  return prepare_checked(std::move(checked), file, limits);
}

SceneSimulation make_simulation(const std::filesystem::path& file, const ElementLimits& limits) {
  return make_simulation(prepare_scene(file, limits));
}

SceneSimulation make_simulation(const SceneDescription& scene, const std::string& label, const ElementLimits& limits) {
  return make_simulation(prepare_scene(scene, label, limits));
}

SceneSimulation make_simulation(PreparedScene prepared) {
  return SceneSimulation{std::move(prepared.scene), Simulation(std::move(prepared.model), prepared.settings)};
}

}  // namespace stiffsoft
