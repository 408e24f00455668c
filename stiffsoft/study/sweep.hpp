#pragma once
/// @file Turning a study into the list of scenes to run: the Cartesian product of the swept
/// values on top of the base scene and the study's fixed `set`, each scene validated and
/// identified by the hash of its resolved JSON.

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <stiffsoft/study/study_spec.hpp>

namespace stiffsoft::study {

/// One scene to run.
struct RunPlan {
  std::map<std::string, nlohmann::json> parameters;  ///< swept path → value of this run
  double x = 0;             ///< value of the x-axis parameter
  std::string series;       ///< label of the other swept values ("" when only x is swept)
  nlohmann::json scene;     ///< the resolved scene (every default written out)
  std::string hash;         ///< 16 hex digits of the FNV-1a hash of scene.dump() without its description
};

/// Every run of the study, grouped by series, x in the order the study gives it.
struct Plan {
  std::vector<RunPlan> runs;                 ///< the sweep
  std::vector<std::string> series;           ///< series labels in first-seen order
  /// Extra reference runs: key "quantity index|series label".
  std::map<std::string, RunPlan> reference_runs;
};

/// Expands the sweep, applies every override and validates each scene with the scene loader.
/// Throws StudyError naming the study file and the JSON path of the offending override
/// (unknown scene key, wrong type or range, missing base scene).
Plan make_plan(const StudySpec& study);

/// The series label of a run's non-x parameters: the values (as `name=value` when the sweep entry
/// has a name) joined by ", " (strings without quotes).
std::string series_label(const StudySpec& study, const std::map<std::string, nlohmann::json>& parameters);

/// 64-bit FNV-1a hash of `text` as 16 hex digits.
std::string fnv1a_hex(const std::string& text);

}  // namespace stiffsoft::study
