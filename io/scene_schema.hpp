#pragma once
/// @file The scene schema: the single source of truth for every key of a scene file
/// (type, default, range or allowed values, unit, doc), in the spirit of PolyFEM's
/// json-specs. The loader (io/scene_loader.hpp) validates against it and fills its
/// defaults; docs/scenes.md is rendered from it by schema_markdown().

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace stiffsoft {

/// Any problem with a scene file: syntax, type, range, unknown key, missing mesh, ...
/// what() is `<file>: <json path>: <what was expected>`, for example
/// `scenes/x.json: bodies[3].density: must be > 0 (got -2)`; a JSON syntax error has
/// `line L, column C` in place of the JSON path.
class SceneError : public std::runtime_error {
 public:
  /// file: the scene file as given; json_path: `bodies[3].density` style (empty for the
  /// root object); expected: what was wrong and what was expected
  SceneError(std::string file, std::string json_path, std::string expected);

  /// the scene file as given by the caller
  const std::string& file() const { return file_; }
  /// where in the document, `bodies[3].density`; `(root)` for the whole document
  const std::string& json_path() const { return json_path_; }
  /// the message without file and path
  const std::string& expected() const { return expected_; }

 private:
  std::string file_;
  std::string json_path_;
  std::string expected_;
};

/// The schema as a JSON list of entries, in document order. Each entry has
/// `pointer` (`/bodies/*/density`; `*` is any list element), `type` (object, list,
/// number, integer, string, vector3, file), `doc`, and where they apply `required`,
/// `default` (null: computed from the scene, explained by `default_doc`), `min`,
/// `exclusive_min`, `max`, `exclusive_max`, `options` (allowed strings), `extensions` (file),
/// `min_length` (list), `unit`, and `when` ({sibling key: [values]}: the key is only
/// allowed when a sibling has one of these values). Two entries with the same pointer
/// are alternatives (a mesh is a file or a primitive object).
const nlohmann::ordered_json& scene_schema();

/// Validates a parsed scene against scene_schema() and returns a copy with every
/// default filled in. Checks types, ranges, allowed values, array lengths, required
/// keys, unknown keys (errors), `when` conditions, and that mesh files exist (resolved
/// against scene_folder) with an allowed extension; mesh paths are replaced by absolute
/// ones. Throws SceneError naming file_label and the JSON path of the first problem.
nlohmann::ordered_json apply_scene_schema(const nlohmann::ordered_json& scene,
                                          const std::filesystem::path& scene_folder,
                                          const std::string& file_label);

/// The schema rendered as a Markdown page (title, conventions, one table per object).
/// docs/scenes.md is exactly this text; a test keeps the two equal.
std::string schema_markdown();

}  // namespace stiffsoft
