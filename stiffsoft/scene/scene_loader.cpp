#include <stiffsoft/scene/scene_loader.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

#include <stiffsoft/coupling/linear_solver/linear_solver.hpp>
#include <stiffsoft/libfem/format_number.hpp>
#include <stiffsoft/scene/printable.hpp>
#include <stiffsoft/scene/scene_fields.hpp>
#include <stiffsoft/scene/scene_text.hpp>
#include <stiffsoft/scene/scene_validation.hpp>

namespace stiffsoft {

namespace {

using Json = nlohmann::ordered_json;

/// Reads the filled JSON (it has passed the schema: every key present where allowed, of the
/// right type) into the structs, key by key from scene_fields.hpp.
struct JsonReader {
  const Json& object;  ///< the JSON object being read

  /// Reads `key` into `value` when the object has it.
  template <class T>
  void operator()(const char* key, T& value, bool /*when*/ = true) const {
    if (object.contains(key)) read(object[key], value);
  }

  template <class T>
  static void read(const Json& j, T& value) {
    if constexpr (scene_fields::Described<T>) {
      scene_fields::fields(JsonReader{j}, value);
    } else if constexpr (std::is_enum_v<T>) {
      const auto& names = scene_fields::EnumNames<T>::names;
      const auto it = std::find(names.begin(), names.end(), j.get<std::string>());
      value = T(it - names.begin());  // the schema allowed only these names
    } else {
      value = j.get<T>();
    }
  }
  static void read(const Json& j, Eigen::Vector3d& v) { v = {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }
  template <class T>
  static void read(const Json& j, std::optional<T>& value) {
    if (j.is_null()) {
      value.reset();
    } else {
      value.emplace();
      read(j, *value);
    }
  }
  template <class T>
  static void read(const Json& j, std::vector<T>& list) {
    list.clear();
    for (const Json& entry : j) read(entry, list.emplace_back());
  }
  /// A mesh is a file name (made absolute by the schema) or a primitive object.
  static void read(const Json& j, MeshDescription& mesh) {
    if (j.is_string()) {
      mesh.file = j.get<std::string>();
    } else {
      read(j, mesh.primitive.emplace());
    }
  }
};

/// A name is how errors, joints and ParaView blocks refer to a body or joint: it must show
/// something, and nothing that garbles a terminal. Throws SceneError at `at`.
void check_name(const std::string& name, const std::string& file, const std::string& at) {
  if (is_blank(name)) throw SceneError(file, at, "must not be empty or only white space");
  if (has_control_character(name))
    throw SceneError(file, at, "must not hold control characters (got \"" + name + "\")");
}

/// contact.pairs: both bodies exist, each pair at most once (in either order).
void check_contact_pairs(const Json& scene, const std::string& file,
                         const std::unordered_map<std::string, std::size_t>& bodies) {
  std::map<std::pair<std::string, std::string>, std::size_t> seen;
  const Json& pairs = scene.at("contact").at("pairs");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string at = "contact.pairs[" + std::to_string(i) + "]";
    std::string a = pairs[i].at("body_a").get<std::string>(), b = pairs[i].at("body_b").get<std::string>();
    if (!bodies.count(a)) throw SceneError(file, at + ".body_a", "no body is named \"" + a + "\"");
    if (!bodies.count(b)) throw SceneError(file, at + ".body_b", "no body is named \"" + b + "\"");
    if (b < a) std::swap(a, b);
    const auto [it, inserted] = seen.emplace(std::make_pair(a, b), i);
    if (!inserted)
      throw SceneError(file, at, "the pair \"" + a + "\", \"" + b + "\" is already given by contact.pairs[" +
                                     std::to_string(it->second) + "]; list each pair once");
  }
}

// Joints: unique names, existing and distinct bodies, usable axes and limits.
void check_joint_relations(const Json& scene, const std::string& file,
                           const std::unordered_map<std::string, std::size_t>& bodies) {
  std::unordered_map<std::string, std::size_t> first_use;
  const Json& joints = scene.at("joints");
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string at = "joints[" + std::to_string(i) + "]";
    JointDescription j;
    JsonReader::read(joints[i], j);
    check_name(j.name, file, at + ".name");
    const auto [it, inserted] = first_use.emplace(j.name, i);
    if (!inserted)
      throw SceneError(file, at + ".name",
                       "duplicate joint name \"" + j.name + "\" (also used by joints[" + std::to_string(it->second) +
                           "]); names must be unique");
    if (!bodies.count(j.body_a))
      throw SceneError(file, at + ".body_a", "no body is named \"" + j.body_a + "\"");
    if (j.body_b != "world" && !bodies.count(j.body_b))
      throw SceneError(file, at + ".body_b", "no body is named \"" + j.body_b + "\" (nor is it \"world\")");
    if (j.body_b == j.body_a) throw SceneError(file, at + ".body_b", "must differ from body_a (\"" + j.body_a + "\")");
    if ((j.kind == JointKind::Hinge || j.kind == JointKind::Prismatic || j.kind == JointKind::ConeTwist) &&
        j.axis.norm() == 0)
      throw SceneError(file, at + ".axis", "must not be zero");
    if ((j.kind == JointKind::Distance || j.kind == JointKind::BoundedDistance) && !j.anchor_b)
      throw SceneError(file, at + ".anchor_b", "required for kind \"" + std::string(scene_fields::enum_name(j.kind)) + "\"");
    if (j.kind == JointKind::BoundedDistance && !j.lower && !j.upper)
      throw SceneError(file, at, "a bounded_distance joint needs lower, upper or both");
    if (j.lower && j.upper && !(*j.lower < *j.upper))
      throw SceneError(file, at + ".upper", "must be > lower (" + std::to_string(*j.lower) + ") (got " +
                                                std::to_string(*j.upper) + ")");
    if (j.kind == JointKind::Hinge || j.kind == JointKind::Prismatic) {
      const double low = j.kind == JointKind::Hinge ? -M_PI : -1e300, high = j.kind == JointKind::Hinge ? M_PI : 1e300;
      const char* unit = j.kind == JointKind::Hinge ? " rad; the initial pose is angle 0" : " m; the initial pose is slide 0";
      if (j.lower && !(*j.lower < 0 && *j.lower > low))
        throw SceneError(file, at + ".lower", "must be < 0" + std::string(j.kind == JointKind::Hinge ? " and > −π" : "") +
                                                  " (got " + std::to_string(*j.lower) + unit + ")");
      if (j.upper && !(*j.upper > 0 && *j.upper < high))
        throw SceneError(file, at + ".upper", "must be > 0" + std::string(j.kind == JointKind::Hinge ? " and < π" : "") +
                                                  " (got " + std::to_string(*j.upper) + unit + ")");
    }
    if (j.kind == JointKind::ConeTwist) {
      if (j.swing && !(*j.swing > 0 && *j.swing < M_PI))
        throw SceneError(file, at + ".swing", "must be > 0 and < π (got " + std::to_string(*j.swing) +
                                                  " rad; the initial pose is bend 0)");
      if (j.twist_lower && !(*j.twist_lower < 0 && *j.twist_lower > -M_PI))
        throw SceneError(file, at + ".twist_lower", "must be < 0 and > −π (got " + std::to_string(*j.twist_lower) +
                                                        " rad; the initial pose is twist 0)");
      if (j.twist_upper && !(*j.twist_upper > 0 && *j.twist_upper < M_PI))
        throw SceneError(file, at + ".twist_upper", "must be > 0 and < π (got " + std::to_string(*j.twist_upper) +
                                                        " rad; the initial pose is twist 0)");
      if ((j.twist_lower || j.twist_upper) && !j.swing)
        throw SceneError(file, at + ".swing",
                         "required with twist_lower or twist_upper: the twist is undefined at bend π, which a swing "
                         "limit (< π) keeps away");
    }
  }
}

/// time: one step at least, and no more steps than a run can count.
void check_time(const Json& scene, const std::string& file) {
  const double dt = scene.at("time").at("dt").get<double>(), duration = scene.at("time").at("duration").get<double>();
  if (!(dt <= duration))
    throw SceneError(file, "time.dt", "must be <= time.duration (" + fem::format_number(duration) + " s) (got " +
                                          fem::format_number(dt) + " s)");
  const double steps = std::ceil(duration / dt);
  if (!(steps <= std::numeric_limits<int>::max()))
    throw SceneError(file, "time.dt",
                     "time.duration / time.dt = " + fem::format_number(steps) + " steps, more than a run can count (" +
                         std::to_string(std::numeric_limits<int>::max()) + "); use a larger dt or a shorter duration");
}

// What a schema entry cannot express: relations between values.
void check_relations(const Json& scene, const std::string& file) {
  check_time(scene, file);
  try {
    check_linear_solver_name(scene.at("solver").at("linear").get<std::string>());
  } catch (const std::invalid_argument& e) {
    throw SceneError(file, "solver.linear", e.what());
  }
  std::unordered_map<std::string, std::size_t> first_use;
  const Json& bodies = scene.at("bodies");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string at = "bodies[" + std::to_string(i) + "]";
    const std::string name = bodies[i].at("name").get<std::string>();
    check_name(name, file, at + ".name");
    const auto [it, inserted] = first_use.emplace(name, i);
    if (!inserted)
      throw SceneError(file, at + ".name",
                       "duplicate body name \"" + name + "\" (also used by bodies[" + std::to_string(it->second) +
                           "]); names must be unique");
    const Json& mesh = bodies[i].at("mesh");
    if (mesh.is_object() && mesh.at("primitive") == "torus" &&
        !(mesh.at("minor_radius").get<double>() < mesh.at("radius").get<double>()))
      throw SceneError(file, at + ".mesh.minor_radius",
                       "must be < radius (" + mesh.at("radius").dump() + ") (got " + mesh.at("minor_radius").dump() +
                           ")");
  }
  check_joint_relations(scene, file, first_use);
  check_contact_pairs(scene, file, first_use);
}

SceneDescription scene_from(const Json& scene, const std::string& name) {
  SceneDescription out;
  out.name = name;
  JsonReader::read(scene, out);
  return out;
}

/// Writes the structs as JSON, key by key from scene_fields.hpp; a conditional key only where
/// its condition holds, so the result lists exactly the keys the schema allows.
struct JsonWriter {
  Json& object;  ///< the JSON object being written

  /// Writes `value` as `key` when `when` holds.
  template <class T>
  void operator()(const char* key, const T& value, bool when = true) const {
    if (when) object[key] = write(value);
  }

  template <class T>
  static Json write(const T& value) {
    if constexpr (scene_fields::Described<T>) {
      Json out = Json::object();
      scene_fields::fields(JsonWriter{out}, value);
      return out;
    } else if constexpr (std::is_enum_v<T>) {
      return scene_fields::enum_name(value);
    } else {
      return value;
    }
  }
  static Json write(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }
  template <class T>
  static Json write(const std::optional<T>& value) {
    return value ? write(*value) : Json(nullptr);
  }
  template <class T>
  static Json write(const std::vector<T>& list) {
    Json out = Json::array();
    for (const T& entry : list) out.push_back(write(entry));
    return out;
  }
  static Json write(const MeshDescription& mesh) {
    return mesh.primitive ? write(*mesh.primitive) : Json(mesh.file.string());
  }
};

}  // namespace

SceneDescription load_scene_from_string(const std::string& text, const std::filesystem::path& scene_folder,
                                        const std::string& file_label, const std::string& name) {
  const Json parsed = parse_scene_text(text, file_label);
  const Json filled = apply_scene_schema(parsed, scene_folder, file_label);
  check_relations(filled, file_label);
  return scene_from(filled, name);
}

SceneDescription load_scene(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file.string(), "", "cannot open the scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return load_scene_from_string(buffer.str(), file.parent_path(), file.string(), file.stem().string());
}

nlohmann::json resolved_scene_json(const SceneDescription& scene) {
  // nlohmann::json (the declared return type) sorts the keys.
  return nlohmann::json(JsonWriter::write(scene));
}

namespace scene_fields {

// The keys the schema allows for this primitive (its `when` conditions), so the resolved JSON
// never lists a key the loader would reject.
bool primitive_uses(const std::string& key, PrimitiveShape::Type type) {
  const auto& entries = scene_schema_entries("/bodies/*/mesh/" + key);
  if (entries.empty()) return false;
  const Json& entry = *entries.front();
  if (!entry.contains("when")) return true;
  const Json& values = entry["when"].at("primitive");
  return std::find(values.begin(), values.end(), enum_name(type)) != values.end();
}

}  // namespace scene_fields

}  // namespace stiffsoft
