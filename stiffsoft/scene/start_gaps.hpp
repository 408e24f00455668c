#pragma once
/// @file The start of a scene against the barrier's activation distance d̂ (docs/robustness.md,
/// "Start gaps"). The barrier acts between surfaces closer than d̂: two bodies that start closer
/// are pushed apart at t = 0 by a force the scene never asked for, and a d̂ that is not small
/// against a body makes its contacts act at a visible distance. Both are refused, with a d̂ that
/// fits, unless the scene sets `contact.check_start_gaps` to false.

#include <string>
#include <vector>

#include <stiffsoft/coupling/model/model.hpp>

namespace stiffsoft {

/// The largest d̂ allowed, as a fraction of the smallest body's size (the diagonal of the box
/// around its initial surface): 1 %.
inline constexpr double kMaxDhatPerBodySize = 1e-2;

/// The smallest body's size (m): the diagonal of the box around its initial surface.
double smallest_body_size(const Model& model);

/// The default d̂ of a scene (m): 1e-3 × its bounding-box diagonal L, as IPC's, but at most
/// kMaxDhatPerBodySize × the smallest body's size, so that the default always passes the check.
double default_dhat(const Model& model);

/// Two different bodies whose initial surfaces are closer than some distance.
struct StartGap {
  int body_a = 0;       ///< index in Model::bodies, < body_b
  int body_b = 0;       ///< index in Model::bodies
  double distance = 0;  ///< smallest distance between their surfaces (m)
};

/// The pairs of different bodies whose initial surfaces (Model::surface(initial_q())) come closer
/// than `below` (m), each with its smallest distance (vertex–triangle and edge–edge, exact for
/// flat triangles), closest first. Only pairs that can touch count: at least one of the two
/// carries DOFs (the contact broad phase's rule; two fixed bodies never meet). A soft body's
/// distance to itself is not included.
std::vector<StartGap> start_gaps_below(const Model& model, double below);

/// Throws SceneError naming `file` when d̂ (m) is above kMaxDhatPerBodySize × the smallest
/// body's size (path `contact.dhat`, naming that body), or when two bodies start closer than
/// d̂ (path `bodies`, naming both, their gap and d̂). Either message suggests a d̂ that passes
/// both checks: at most half the smallest gap and 1 % of the smallest body, rounded down to 3
/// digits. `dhat_given`: whether the scene set contact.dhat (otherwise the message says it is
/// the default, 1e-3 × the scene's bounding-box diagonal). Body i of the model is bodies[i] of
/// the scene.
void check_start_gaps(const Model& model, double dhat, bool dhat_given, const std::string& file);

}  // namespace stiffsoft
