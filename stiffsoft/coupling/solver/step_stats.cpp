#include <stiffsoft/coupling/solver/step_stats.hpp>

namespace stiffsoft {

const std::vector<StepStatsColumn>& step_stats_columns() {
  static const std::vector<StepStatsColumn> columns{
      {"step", [](const StepStats& s) { return double(s.step); }},
      {"time", [](const StepStats& s) { return s.time; }},
      {"newton_iterations", [](const StepStats& s) { return double(s.newton.iterations); }},
      {"linear_iterations", [](const StepStats& s) { return double(s.newton.linear_iterations); }},
      {"linear_fallbacks", [](const StepStats& s) { return double(s.newton.linear_fallbacks); }},
      {"line_search_steps", [](const StepStats& s) { return double(s.newton.line_search_steps); }},
      {"line_search_halvings", [](const StepStats& s) { return double(s.newton.line_search_halvings); }},
      {"smallest_ccd_step", [](const StepStats& s) { return s.newton.smallest_ccd_step; }},
      {"ccd_limited_iterations", [](const StepStats& s) { return double(s.newton.ccd_limited_iterations); }},
      {"revised_directions", [](const StepStats& s) { return double(s.newton.revised_directions); }},
      {"entering_directions", [](const StepStats& s) { return double(s.newton.entering_directions); }},
      {"converged", [](const StepStats& s) { return s.newton.converged ? 1.0 : 0.0; }},
      {"contacts", [](const StepStats& s) { return double(s.contacts); }},
      {"smallest_distance", [](const StepStats& s) { return s.smallest_distance; }},
      {"kinetic_energy", [](const StepStats& s) { return s.kinetic_energy; }},
      {"potential_energy", [](const StepStats& s) { return s.potential_energy; }},
      {"momentum_x", [](const StepStats& s) { return s.linear_momentum.x(); }},
      {"momentum_y", [](const StepStats& s) { return s.linear_momentum.y(); }},
      {"momentum_z", [](const StepStats& s) { return s.linear_momentum.z(); }},
      {"orthogonality_error", [](const StepStats& s) { return s.orthogonality_error; }},
      {"elastic_energy", [](const StepStats& s) { return s.elastic_energy; }},
      {"inverted_tets", [](const StepStats& s) { return double(s.inverted_tets); }},
      {"friction_relags", [](const StepStats& s) { return double(s.friction_relags); }},
      {"friction_lag_error", [](const StepStats& s) { return s.friction_lag_error; }},
      {"sticking", [](const StepStats& s) { return double(s.sticking); }},
      {"sliding", [](const StepStats& s) { return double(s.sliding); }},
      {"stick_slip_flips", [](const StepStats& s) { return double(s.stick_slip_flips); }},
      {"kappa", [](const StepStats& s) { return s.kappa; }},
      {"joint_error", [](const StepStats& s) { return s.joint_error; }},
      {"joint_force", [](const StepStats& s) { return s.joint_force; }},
      {"sleeping_bodies", [](const StepStats& s) { return double(s.sleeping_bodies); }},
      {"seconds_broad_phase", [](const StepStats& s) { return s.times.broad_phase; }},
      {"seconds_ccd", [](const StepStats& s) { return s.times.ccd; }},
      {"seconds_assembly", [](const StepStats& s) { return s.times.assembly; }},
      {"seconds_solve", [](const StepStats& s) { return s.times.solve; }},
      {"seconds_step", [](const StepStats& s) { return s.seconds; }},
  };
  return columns;
}

std::vector<std::string> step_stats_column_names() {
  std::vector<std::string> names;
  for (const StepStatsColumn& c : step_stats_columns()) names.emplace_back(c.name);
  return names;
}

std::vector<double> step_stats_row(const StepStats& s) {
  std::vector<double> row;
  for (const StepStatsColumn& c : step_stats_columns()) row.push_back(c.value(s));
  return row;
}

}  // namespace stiffsoft
