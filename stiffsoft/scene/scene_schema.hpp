#pragma once
/// @file The scene schema: the single source of truth for every key of a scene file
/// (type, default, range or allowed values, unit, doc), in the spirit of PolyFEM's
/// json-specs. A default that a description struct holds is taken from that struct
/// (stiffsoft/scene/scene.hpp), so each is written once. The loader
/// (stiffsoft/scene/scene_loader.hpp) validates against it and fills its defaults through
/// apply_scene_schema() (scene_validation.hpp); docs/scenes.md is rendered from it by
/// schema_markdown() (schema_markdown.hpp), which `stiffsoft schema --markdown` prints.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace stiffsoft {

/// Any problem with a scene file: syntax, type, range, unknown key, missing mesh, ...
/// what() is `<file>: <json path>: <what was expected>`, for example
/// `scenes/x.json: bodies[3].density: must be > 0 (got -2)`; a JSON syntax error has
/// `line L, column C` in place of the JSON path. Bytes that are not printable (invalid UTF-8,
/// control characters) are shown as `\xNN` in every part (printable(), printable.hpp), so the
/// accessors return the escaped text too.
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
/// number, integer, string, boolean, vector3, file), `doc`, and where they apply `required`,
/// `default` (null: computed from the scene, explained by `default_doc`), `min`,
/// `exclusive_min`, `max`, `exclusive_max`, `options` (allowed strings), `extensions` (file),
/// `min_length` (list), `unit`, and `when` ({sibling key: [values]}: the key is only
/// allowed when a sibling has one of these values). Two entries with the same pointer
/// are alternatives (a mesh is a file or a primitive object). Defaults held by the
/// description structs are the values of default-constructed structs (TimeDescription{},
/// BodyDescription{}, ...). Parsed once, on the first call.
const nlohmann::ordered_json& scene_schema();

/// The schema's entries with this pointer (`/bodies/*/density`), in document order: one, or
/// more where the schema gives alternatives; none for a pointer it does not have. Looked up in
/// an index built once, on the first call (a scene of 562 bodies looks up thousands).
const std::vector<const nlohmann::ordered_json*>& scene_schema_entries(const std::string& pointer);

/// A key of an object entry and its first schema entry.
using SchemaChild = std::pair<std::string, const nlohmann::ordered_json*>;

/// The direct children of the object entry at `pointer` (`/` for the root), each key once with
/// its first entry, in document order; none for a pointer without children. From the same index.
const std::vector<SchemaChild>& scene_schema_children(const std::string& pointer);

/// A list of the schema (`options`, `extensions`, `when` values) as text for messages and docs:
/// strings as they are, anything else as JSON, joined by `separator`.
std::string schema_list_text(const nlohmann::ordered_json& list, const std::string& separator = ", ");

}  // namespace stiffsoft
