#pragma once
/// @file Checking a parsed scene file against the scene schema (scene_schema.hpp) and
/// filling in its defaults.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

/// Validates a parsed scene against scene_schema() and returns a copy with every
/// default filled in. Checks types, ranges, allowed values, array lengths, required
/// keys, unknown keys (errors), `when` conditions, and that mesh files exist (resolved
/// against scene_folder) with an allowed extension; mesh paths are replaced by absolute
/// ones. Throws SceneError naming file_label and the JSON path of the first problem.
nlohmann::ordered_json apply_scene_schema(const nlohmann::ordered_json& scene,
                                          const std::filesystem::path& scene_folder,
                                          const std::string& file_label);

}  // namespace stiffsoft
