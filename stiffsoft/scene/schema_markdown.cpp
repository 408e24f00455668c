#include <stiffsoft/scene/schema_markdown.hpp>

#include <iomanip>
#include <sstream>
#include <vector>

#include <stiffsoft/scene/element_limits.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

namespace {

using Json = nlohmann::ordered_json;

// A list on one line: strings bare, other values as JSON.
std::string markdown_key(const std::string& pointer) {
  if (pointer == "/") return "(root)";
  std::string key;
  std::stringstream parts(pointer.substr(1));
  std::string part;
  while (std::getline(parts, part, '/')) {
    if (part == "*") key += "[]";
    else key += (key.empty() ? "" : ".") + part;
  }
  return key;
}

std::string markdown_type(const Json& entry) {
  const std::string type = entry.at("type");
  if (type == "vector3") return "[x, y, z]";
  if (type == "file") return "string (file)";
  return type;
}

// Numbers as people write them: 0.01, -9.81, 1e+08 (not 100000000.0).
std::string markdown_value(const Json& value) {
  if (value.is_number()) {
    std::ostringstream out;
    out << std::setprecision(15) << value.get<double>();
    return out.str();
  }
  if (value.is_array()) {
    std::string out;
    for (const auto& item : value) out += (out.empty() ? "" : ", ") + markdown_value(item);
    return "[" + out + "]";
  }
  return value.dump();
}

std::string markdown_default(const Json& entry) {
  if (entry.value("required", false)) return "**required**";
  if (!entry.contains("default")) return "";
  if (entry["default"].is_null()) return "null → " + entry.value("default_doc", std::string("computed"));
  return "`" + markdown_value(entry["default"]) + "`";
}

std::string markdown_allowed(const Json& entry) {
  std::vector<std::string> parts;
  if (entry.contains("exclusive_min")) parts.push_back("> " + markdown_value(entry["exclusive_min"]));
  if (entry.contains("min")) parts.push_back("≥ " + markdown_value(entry["min"]));
  if (entry.contains("exclusive_max")) parts.push_back("< " + markdown_value(entry["exclusive_max"]));
  if (entry.contains("max")) parts.push_back("≤ " + markdown_value(entry["max"]));
  if (entry.contains("options")) {
    std::string options;
    // Appended piece by piece: `"`" + std::string` trips GCC 12's -Wrestrict (a false positive).
    for (const auto& option : entry["options"]) {
      if (!options.empty()) options += ", ";
      options += '`';
      options += option.get<std::string>();
      options += '`';
    }
    parts.push_back(options);
  }
  if (entry.contains("extensions")) parts.push_back(schema_list_text(entry["extensions"]));
  if (entry.contains("min_length")) parts.push_back("at least " + entry["min_length"].dump() + " item(s)");
  if (entry.contains("when"))
    for (const auto& [sibling, values] : entry["when"].items())
      parts.push_back("only when " + sibling + " is " + schema_list_text(values, ", "));
  std::string out;
  for (const auto& part : parts) out += (out.empty() ? "" : "; ") + part;
  return out;
}

}  // namespace

std::string schema_markdown() {
  std::string md;
  md += "# Scene files\n\n";
  md += "<!-- Generated from stiffsoft/scene/scene_schema.cpp (defaults held by the structs of "
        "stiffsoft/scene/scene.hpp) by stiffsoft::schema_markdown(); do not edit by hand.\n";
  md += "     Regenerate with: build/release/apps/stiffsoft schema --markdown > docs/scenes.md -->\n\n";
  md += "A scene is one JSON file. Units are SI (metres, kilograms, seconds, radians except where a key "
        "says degrees); y is up. Run one with `stiffsoft run scenes/X.json -o out/X`.\n\n";
  md += "- Every key is listed below with its type, default, allowed values, unit and meaning. "
        "Unknown keys are errors, so a typo never passes silently.\n";
  md += "- `null → ...` defaults are relative to the scene's size: the bounding-box diagonal is the "
        "diagonal of the box around all bodies in their initial pose. Absent or null, the loader keeps them "
        "unset (null in `scene.resolved.json`) and the simulator computes them.\n";
  md += "- A mesh is either a file path (`.obj`, `.stl`; relative to the scene file's folder) or a "
        "primitive object; a primitive accepts only the keys its shape uses.\n";
  md += "- A pose is applied as x = R·(scale ∘ x̄) + position with R = Rz·Ry·Rx from `rotation_deg`.\n";
  md += "- Every error names the file and the JSON path, e.g. "
        "`scenes/x.json: bodies[3].density: must be > 0 (got -2)`.\n";
  md += "- Bodies must start more than d̂ apart (closest surface points; no overlaps), and d̂ must be at most 1 % "
        "of the smallest body's bounding-box diagonal. Both are checked, and the error suggests a d̂ that fits, unless "
        "`contact.check_start_gaps` is false (docs/robustness.md).\n";
  md += "- Every number must be finite; velocities, positions and sizes have bounds (the allowed column). A body may "
        "ask for at most " + std::to_string(ElementLimits{}.max_tets) + " tetrahedra and " +
        std::to_string(ElementLimits{}.max_triangles) + " primitive triangles, estimated before meshing "
        "(`stiffsoft run --max-tets N --max-triangles N` raise them).\n\n";
  md += "| key | type | default | allowed | unit | description |\n";
  md += "|---|---|---|---|---|---|\n";
  for (const auto& entry : scene_schema()) {
    md += "| `" + markdown_key(entry.at("pointer")) + "` | " + markdown_type(entry) + " | " +
          markdown_default(entry) + " | " + markdown_allowed(entry) + " | " +
          entry.value("unit", std::string("")) + " | " + entry.value("doc", std::string("")) + " |\n";
  }
  return md;
}

}  // namespace stiffsoft
