#pragma once
/// @file Scene JSON as text: parsing a scene file with every problem located (line and column,
/// or the JSON path), and checking JSON built in code before it is written out as text.

#include <string>

#include <nlohmann/json.hpp>

namespace stiffsoft {

/// Parses the text of a scene file. Throws SceneError naming `file_label` and where:
/// - a syntax error: `line L, column C: invalid JSON: <reason>`;
/// - a number a double cannot hold: `<json path>: the number 1e400 is too large for a double
///   (largest: 1.8e308)`; one that would round to 0 (1e-400) likewise;
/// - a key written twice in one object (JSON leaves that open; the parser would keep one copy
///   silently): `<json path>: the key "dt" is given twice in this object`.
/// Bytes that are not printable are shown escaped (printable.hpp).
nlohmann::ordered_json parse_scene_text(const std::string& text, const std::string& file_label);

/// Checks JSON built in code (a SceneDescription's resolved_scene_json()) for what text cannot
/// carry: a number that is not finite (JSON has no NaN or infinity; they would be written as
/// null) and a string that is not valid UTF-8. Throws SceneError naming `file_label` and the JSON
/// path of the first such value.
void check_json_values(const nlohmann::ordered_json& json, const std::string& file_label);

}  // namespace stiffsoft
