#pragma once
/// @file Reading a scene file into a SceneDescription, and writing one back as JSON.
/// The only place that turns scene JSON into settings structs (see stiffsoft/scene/scene_schema.hpp
/// for the keys, docs/scenes.md for the rendered table).

#include <filesystem>

#include <nlohmann/json.hpp>

#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

/// Reads, validates and converts a scene file; every default is filled in.
/// Checks the text (parse_scene_text(): syntax, numbers a double cannot hold, keys given
/// twice), everything scene_schema() states (types, ranges, allowed values, array
/// lengths, integers that fit an int, required and unknown keys, mesh files existing with an
/// allowed extension, resolved against the scene file's folder) plus what a schema entry
/// cannot: unique body and joint names that show something and hold no control character,
/// dt ≤ duration and a step count that fits an int, torus minor_radius < radius, joints and
/// contact pairs naming existing bodies. Relative defaults (contact.dhat,
/// contact.eps_v, contact.kappa, solver.tolerance, output.frame_dt) stay unset.
/// SceneDescription::name is the file's stem.
/// Throws SceneError (`<file>: <json path>: <what was expected>`; JSON syntax errors
/// give `<file>: line L, column C: ...`); an unreadable file is a SceneError too.
SceneDescription load_scene(const std::filesystem::path& file);

/// Like load_scene, from text already in memory. scene_folder resolves relative mesh
/// paths; file_label names the source in error messages; name becomes SceneDescription::name.
SceneDescription load_scene_from_string(const std::string& text, const std::filesystem::path& scene_folder,
                                        const std::string& file_label, const std::string& name);

/// The scene as JSON with every default written out: the content of
/// `OUT/scene.resolved.json`. Relative defaults that are still unset are written as
/// null (the simulator resolves them against the bounding-box diagonal); mesh files are
/// absolute paths; a primitive lists exactly the keys its shape uses. The result
/// validates against the schema, and loading it gives back the same SceneDescription
/// (apart from `name`, which comes from the file name).
nlohmann::json resolved_scene_json(const SceneDescription& scene);

}  // namespace stiffsoft
