#include <stiffsoft/scene/scene_validation.hpp>

#include <algorithm>
#include <cctype>
#include <limits>
#include <string>
#include <vector>

#include <stiffsoft/libfem/format_number.hpp>
#include <stiffsoft/scene/printable.hpp>

namespace stiffsoft {

namespace {

using Json = nlohmann::ordered_json;

// A value as it appears in an error message: short, on one line.
std::string shown(const Json& value) {
  std::string kind;
  if (value.is_string()) kind = "string ";
  else if (value.is_boolean()) kind = "boolean ";
  else if (value.is_object()) return "an object";
  else if (value.is_array()) return "an array of " + std::to_string(value.size());
  else if (value.is_null()) return "null";
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return kind + text;
}

// Human name of an entry's type, for "must be ..." messages.
std::string type_phrase(const Json& entry) {
  const std::string type = entry.at("type");
  if (type == "object") return "an object";
  if (type == "list") return "a list";
  if (type == "number") return "a number";
  if (type == "integer") return "an integer";
  if (type == "string") return "a string";
  if (type == "boolean") return "true or false";
  if (type == "vector3") return "an array of 3 numbers";
  if (type == "file") return "a mesh file path (string)";
  return type;
}

bool type_matches(const Json& entry, const Json& value) {
  // null stands for a computed default (relative to the scene's size), so it is a valid
  // value wherever that is the default; resolved scenes write it that way.
  if (value.is_null()) return entry.contains("default") && entry["default"].is_null();
  const std::string type = entry.at("type");
  if (type == "object") return value.is_object();
  if (type == "list" || type == "vector3") return value.is_array();
  if (type == "number") return value.is_number();
  if (type == "integer") return value.is_number_integer();
  if (type == "string" || type == "file") return value.is_string();
  if (type == "boolean") return value.is_boolean();
  return false;
}

// Levenshtein distance, for "did you mean" on unknown keys.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string child_pointer(const std::string& pointer, const std::string& key) {
  return pointer == "/" ? "/" + key : pointer + "/" + key;
}

std::string child_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

class Validator {
 public:
  Validator(const std::filesystem::path& folder, const std::string& file)
      : folder_(folder), file_(file) {}

  Json validate(const Json& value, const std::string& pointer, const std::string& path) const {
    const Json& entry = pick_entry(value, pointer, path);
    const std::string type = entry.at("type");
    if (value.is_null()) return value;
    if (type == "object") return validate_object(value, entry, pointer, path);
    if (type == "list") return validate_list(value, entry, pointer, path);
    if (type == "vector3") return validate_vector3(value, entry, path);
    if (type == "number" || type == "integer") {
      // Integers are read into an int: a larger one would wrap around silently.
      if (type == "integer" && !(value.get<double>() >= std::numeric_limits<int>::min() &&
                                 value.get<double>() <= std::numeric_limits<int>::max()))
        fail(path, "must be an integer between " + std::to_string(std::numeric_limits<int>::min()) + " and " +
                       std::to_string(std::numeric_limits<int>::max()) + " (got " + value.dump() + ")");
      check_range(value, entry, path);
      return value;
    }
    if (type == "boolean") return value;
    if (type == "string") {
      if (entry.contains("options") &&
          std::find(entry["options"].begin(), entry["options"].end(), value) == entry["options"].end())
        fail(path, "unknown value " + value.dump() + " (allowed: " + schema_list_text(entry["options"]) + ")");
      return value;
    }
    if (type == "file") return validate_file(value, entry, path);
    fail(path, "schema error: unknown type " + type);
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw SceneError(file_, path, what);
  }

  // The schema entry for this value; where the schema gives alternatives, the one whose
  // type fits.
  const Json& pick_entry(const Json& value, const std::string& pointer, const std::string& path) const {
    const auto& entries = scene_schema_entries(pointer);
    std::string expected;
    for (const Json* entry : entries) {
      if (type_matches(*entry, value)) return *entry;
      expected += (expected.empty() ? "" : " or ") + type_phrase(*entry);
    }
    fail(path, "must be " + expected + " (got " + shown(value) + ")");
  }

  void check_range(const Json& value, const Json& entry, const std::string& path) const {
    const double x = value.get<double>();
    // Shortest round-trip text: 1e+06 rather than 1000000.0.
    const auto text = [](const Json& number) { return fem::format_number(number.get<double>()); };
    if (entry.contains("exclusive_min") && !(x > entry["exclusive_min"].get<double>()))
      fail(path, "must be > " + text(entry["exclusive_min"]) + " (got " + text(value) + ")");
    if (entry.contains("min") && !(x >= entry["min"].get<double>()))
      fail(path, "must be >= " + text(entry["min"]) + " (got " + text(value) + ")");
    if (entry.contains("exclusive_max") && !(x < entry["exclusive_max"].get<double>()))
      fail(path, "must be < " + text(entry["exclusive_max"]) + " (got " + text(value) + ")");
    if (entry.contains("max") && !(x <= entry["max"].get<double>()))
      fail(path, "must be <= " + text(entry["max"]) + " (got " + text(value) + ")");
  }

  Json validate_vector3(const Json& value, const Json& entry, const std::string& path) const {
    if (value.size() != 3)
      fail(path, "must be an array of 3 numbers (got an array of " + std::to_string(value.size()) + ")");
    for (std::size_t i = 0; i < 3; ++i) {
      const std::string item_path = path + "[" + std::to_string(i) + "]";
      if (!value[i].is_number()) fail(item_path, "must be a number (got " + shown(value[i]) + ")");
      check_range(value[i], entry, item_path);
    }
    return value;
  }

  Json validate_list(const Json& value, const Json& entry, const std::string& pointer,
                     const std::string& path) const {
    if (entry.contains("min_length") && value.size() < entry["min_length"].get<std::size_t>())
      fail(path, "must hold at least " + entry["min_length"].dump() + " item(s) (got " +
                     std::to_string(value.size()) + ")");
    Json out = Json::array();
    for (std::size_t i = 0; i < value.size(); ++i)
      out.push_back(validate(value[i], child_pointer(pointer, "*"), path + "[" + std::to_string(i) + "]"));
    return out;
  }

  Json validate_file(const Json& value, const Json& entry, const std::string& path) const {
    const std::filesystem::path given = value.get<std::string>();
    std::string extension = given.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const Json& allowed = entry.at("extensions");
    if (std::find(allowed.begin(), allowed.end(), extension) == allowed.end())
      fail(path, "unsupported mesh file extension \"" + extension + "\" (allowed: " + schema_list_text(allowed) + ")");
    // Relative paths are relative to the scene file, so a scene folder can be moved whole.
    const std::filesystem::path resolved = std::filesystem::absolute(folder_ / given).lexically_normal();
    if (!std::filesystem::is_regular_file(resolved))
      fail(path, "mesh file not found: " + resolved.string() + " (relative paths are resolved against " +
                     "the scene file's folder)");
    return resolved.string();
  }

  // Whether a `when` condition holds: the sibling's value (given or default) is listed.
  static bool condition_holds(const Json& entry, const Json& object, const std::string& pointer) {
    if (!entry.contains("when")) return true;
    for (const auto& [sibling, values] : entry["when"].items()) {
      Json sibling_value;
      if (object.contains(sibling)) {
        sibling_value = object[sibling];
      } else {
        for (const Json* e : scene_schema_entries(child_pointer(pointer, sibling)))
          if (e->contains("default")) sibling_value = (*e)["default"];
      }
      if (std::find(values.begin(), values.end(), sibling_value) == values.end()) return false;
    }
    return true;
  }

  Json validate_object(const Json& value, const Json& /*entry*/, const std::string& pointer,
                       const std::string& path) const {
    const auto& children = scene_schema_children(pointer);
    std::string allowed;
    for (const auto& child : children) allowed += (allowed.empty() ? "" : ", ") + child.first;
    // Unknown keys first, in the order written, so a typo is reported as such rather than
    // as the missing key it was meant to be.
    for (const auto& item : value.items()) {
      const bool known = std::any_of(children.begin(), children.end(),
                                     [&](const auto& child) { return child.first == item.key(); });
      if (known) continue;
      std::string hint;
      for (const auto& child : children) {
        const std::size_t tolerance = std::max<std::size_t>(1, child.first.size() / 3);
        if (edit_distance(child.first, item.key()) <= tolerance) hint = "; did you mean \"" + child.first + "\"?";
      }
      fail(child_path(path, item.key()), "unknown key (allowed: " + allowed + ")" + hint);
    }
    Json out = Json::object();
    for (const auto& [key, entry] : children) {
      const std::string p = child_pointer(pointer, key);
      const std::string q = child_path(path, key);
      const bool applies = condition_holds(*entry, value, pointer);
      if (value.contains(key)) {
        if (!applies) {
          std::string condition;
          for (const auto& [sibling, values] : (*entry)["when"].items())
            condition = sibling + " is " + schema_list_text(values, " or ") + " (it is " +
                        (value.contains(sibling) ? value[sibling].dump() : std::string("unset")) + ")";
          fail(q, "only allowed when " + condition);
        }
        out[key] = validate(value[key], p, q);
      } else if (entry->value("required", false)) {
        fail(q, "required key is missing");
      } else if (!applies) {
        continue;
      } else if (entry->contains("default")) {
        out[key] = (*entry)["default"];
      } else if ((*entry)["type"] == "object") {
        out[key] = validate(Json::object(), p, q);
      }
    }
    return out;
  }

  std::filesystem::path folder_;
  std::string file_;
};

}  // namespace

// Every part is made printable here, once, so no message can carry a raw byte from a file.
SceneError::SceneError(std::string file, std::string json_path, std::string expected)
    : std::runtime_error(printable(file) + ": " + (json_path.empty() ? std::string("(root)") : printable(json_path)) +
                         ": " + printable(expected)),
      file_(printable(file)),
      json_path_(json_path.empty() ? "(root)" : printable(json_path)),
      expected_(printable(expected)) {}

nlohmann::ordered_json apply_scene_schema(const nlohmann::ordered_json& scene,
                                          const std::filesystem::path& scene_folder,
                                          const std::string& file_label) {
  return Validator(scene_folder, file_label).validate(scene, "/", "");
}

}  // namespace stiffsoft
