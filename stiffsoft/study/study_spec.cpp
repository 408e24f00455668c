#include <stiffsoft/study/study_spec.hpp>

#include <fstream>
#include <set>
#include <sstream>

#include <stiffsoft/study/builtin_references.hpp>

namespace stiffsoft::study {

namespace {

using nlohmann::json;

/// Throws StudyError `<file>: <path>: <what>`.
[[noreturn]] void fail(const StudySpec& s, const std::string& path, const std::string& what) {
  throw StudyError(s.file.string() + ": " + (path.empty() ? "/" : path) + ": " + what);
}

void check_keys(const StudySpec& s, const json& j, const std::string& path, const std::set<std::string>& allowed) {
  if (!j.is_object()) fail(s, path, "expected an object");
  for (const auto& [key, value] : j.items())
    if (!allowed.contains(key)) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(s, path + "/" + key, "unknown key (allowed: " + list + ")");
    }
}

const json& required(const StudySpec& s, const json& j, const std::string& path, const std::string& key) {
  if (!j.contains(key)) fail(s, path + "/" + key, "missing (required)");
  return j.at(key);
}

std::string string_at(const StudySpec& s, const json& j, const std::string& path) {
  if (!j.is_string()) fail(s, path, "expected a string, got " + j.dump());
  return j.get<std::string>();
}

double number_at(const StudySpec& s, const json& j, const std::string& path) {
  if (!j.is_number()) fail(s, path, "expected a number, got " + j.dump());
  return j.get<double>();
}

void check_pointer_object(const StudySpec& s, const json& j, const std::string& path) {
  if (!j.is_object()) fail(s, path, "expected an object of JSON pointer → value");
  for (const auto& [key, value] : j.items())
    if (key.empty() || key[0] != '/') fail(s, path + "/" + key, "keys are JSON pointers into the scene, starting with '/'");
}

std::map<std::string, double> parse_expected(const StudySpec& s, const json& e, const std::string& path) {
  std::map<std::string, double> out;
  if (e.is_number()) out[""] = e.get<double>();
  else if (e.is_object()) {
    for (const auto& [key, value] : e.items()) out[key] = number_at(s, value, path + "/" + key);
  } else fail(s, path, "expected a number or an object of series label → number");
  return out;
}

Field parse_field(const StudySpec& s, const std::string& name, const std::string& path) {
  static const std::map<std::string, Field> fields{
      {"position", Field::Position},         {"velocity", Field::Velocity},
      {"angular_velocity", Field::AngularVelocity}, {"affine_matrix", Field::Affine},
      {"kinetic_energy", Field::KineticEnergy}, {"contact_force", Field::ContactForce},
      {"friction_force", Field::FrictionForce}, {"displacement", Field::Position}};
  const auto it = fields.find(name);
  if (it == fields.end())
    fail(s, path, "unknown field '" + name +
                      "' (position, displacement, velocity, angular_velocity, affine_matrix, kinetic_energy, "
                      "contact_force, friction_force)");
  return it->second;
}

ReferenceSpec parse_reference(const StudySpec& s, const json& j, const std::string& path, int components) {
  check_keys(s, j, path, {"analytic", "builtin", "finest", "richardson", "order", "run"});
  ReferenceSpec r;
  int kinds = 0;
  if (j.contains("analytic")) {
    ++kinds;
    r.kind = ReferenceKind::Analytic;
    const json& a = j.at("analytic");
    if (a.is_string()) r.expressions = {a.get<std::string>()};
    else if (a.is_array()) {
      for (std::size_t i = 0; i < a.size(); ++i)
        r.expressions.push_back(string_at(s, a[i], path + "/analytic/" + std::to_string(i)));
    } else fail(s, path + "/analytic", "expected an expression string or an array of them");
  }
  if (j.contains("builtin")) {
    ++kinds;
    r.kind = ReferenceKind::Analytic;
    r.builtin = string_at(s, j.at("builtin"), path + "/builtin");
    const BuiltinReference* b = find_builtin_reference(r.builtin);
    if (!b) {
      std::string list;
      for (const BuiltinReference& x : builtin_references()) list += (list.empty() ? "" : ", ") + x.name;
      fail(s, path + "/builtin", "unknown built-in reference '" + r.builtin + "' (known: " + list + ")");
    }
    for (const std::string& c : b->constants)
      if (!s.constants.contains(c))
        fail(s, "/constants/" + c, "missing: the built-in reference '" + r.builtin + "' needs it");
    r.expressions = b->expressions;
  }
  if (j.contains("finest")) {
    ++kinds;
    r.kind = ReferenceKind::Finest;
    const std::string f = string_at(s, j.at("finest"), path + "/finest");
    if (f != "smallest" && f != "largest") fail(s, path + "/finest", "expected \"smallest\" or \"largest\" (which x is finest)");
    r.finest_is_largest = f == "largest";
  }
  if (j.contains("richardson")) {
    ++kinds;
    r.kind = ReferenceKind::Richardson;
    const std::string f = string_at(s, j.at("richardson"), path + "/richardson");
    if (f != "smallest" && f != "largest") fail(s, path + "/richardson", "expected \"smallest\" or \"largest\" (which x is finest)");
    r.finest_is_largest = f == "largest";
    if (j.contains("order")) {
      r.order = number_at(s, j.at("order"), path + "/order");
      if (!(*r.order > 0)) fail(s, path + "/order", "expected a positive order");
    }
  } else if (j.contains("order")) {
    fail(s, path + "/order", "only used with \"richardson\"");
  }
  if (j.contains("run")) {
    ++kinds;
    r.kind = ReferenceKind::Run;
    check_pointer_object(s, j.at("run"), path + "/run");
    r.overrides = j.at("run");
  }
  if (kinds != 1)
    fail(s, path, "give exactly one of analytic, builtin, finest, richardson, run (got " + std::to_string(kinds) + ")");
  if (r.kind == ReferenceKind::Analytic && int(r.expressions.size()) != components)
    fail(s, path, "the reference has " + std::to_string(r.expressions.size()) + " expressions, the quantity compares " +
                      std::to_string(components) + " components");
  return r;
}

QuantitySpec parse_quantity(const StudySpec& s, const json& j, const std::string& path) {
  check_keys(s, j, path, {"name", "body", "field", "stats", "point", "component", "at", "reduce", "crossing",
                          "relative", "reference", "unit", "window", "expected_order"});
  QuantitySpec q;
  q.json_path = path;
  q.name = string_at(s, required(s, j, path, "name"), path + "/name");
  if (q.name.empty() || q.name.find_first_of(",\"\n") != std::string::npos)
    fail(s, path + "/name", "expected a non-empty name without ',', '\"' or line breaks");
  int sources = 0, size = 1;
  bool displacement = false;
  if (j.contains("field")) {
    ++sources;
    q.source = Source::Body;
    q.body = string_at(s, required(s, j, path, "body"), path + "/body");
    const std::string f = string_at(s, j.at("field"), path + "/field");
    q.field = parse_field(s, f, path + "/field");
    displacement = f == "displacement";
    size = field_size(q.field);
  }
  if (j.contains("stats")) {
    ++sources;
    q.source = Source::Stats;
    q.column = string_at(s, j.at("stats"), path + "/stats");
  }
  if (j.contains("point")) {
    ++sources;
    q.source = Source::Point;
    q.body = string_at(s, required(s, j, path, "body"), path + "/body");
    const json& p = j.at("point");
    if (!p.is_array() || p.size() != 3) fail(s, path + "/point", "expected [x, y, z] (m), the node's rest position");
    for (int i = 0; i < 3; ++i) q.rest_point[i] = number_at(s, p[i], path + "/point/" + std::to_string(i));
    size = 3;
  }
  if (sources != 1) fail(s, path, "give exactly one of field (with body), stats, point (with body)");
  if (j.contains("body") && q.source == Source::Stats) fail(s, path + "/body", "not used with stats");
  std::vector<int> components;
  if (j.contains("component")) {
    const json& c = j.at("component");
    auto one = [&](const json& v, const std::string& p) {
      if (v.is_number_integer()) {
        const int i = v.get<int>();
        if (i < 0 || i >= size) fail(s, p, "component index out of range [0, " + std::to_string(size) + ")");
        return i;
      }
      const std::string n = string_at(s, v, p);
      if (n == "x" || n == "y" || n == "z") {
        if (size != 3) fail(s, p, "x/y/z need a 3-component field");
        return int(n[0] - 'x');
      }
      if (n == "norm") return -1;
      fail(s, p, "expected an index, \"x\", \"y\", \"z\" or \"norm\"");
    };
    if (c.is_array()) {
      for (std::size_t i = 0; i < c.size(); ++i) components.push_back(one(c[i], path + "/component/" + std::to_string(i)));
    } else {
      components.push_back(one(c, path + "/component"));
    }
  }
  q.components = components;
  int compared = 0;
  if (components.size() == 1 && components[0] == -1) compared = 1;
  else compared = components.empty() ? size : int(components.size());
  for (int c : components)
    if (c == -1 && components.size() != 1) fail(s, path + "/component", "\"norm\" cannot be combined with other components");
  if (j.contains("at")) {
    q.reduction = Reduction::At;
    q.time = number_at(s, j.at("at"), path + "/at");
    if (j.contains("reduce")) fail(s, path + "/reduce", "give either at or reduce");
  } else if (j.contains("reduce")) {
    static const std::map<std::string, Reduction> reductions{
        {"end", Reduction::End},       {"max", Reduction::Max},           {"min", Reduction::Min},
        {"max_abs", Reduction::MaxAbs}, {"change", Reduction::Change},    {"crossing", Reduction::Crossing},
        {"trajectory", Reduction::Trajectory}};
    const std::string r = string_at(s, j.at("reduce"), path + "/reduce");
    const auto it = reductions.find(r);
    if (it == reductions.end())
      fail(s, path + "/reduce", "unknown reduction '" + r + "' (end, max, min, max_abs, change, crossing, trajectory)");
    q.reduction = it->second;
  }
  if ((q.reduction == Reduction::Max || q.reduction == Reduction::Min || q.reduction == Reduction::MaxAbs ||
       q.reduction == Reduction::Crossing) &&
      compared != 1)
    fail(s, path + "/reduce", "this reduction needs a scalar: choose one component (or \"norm\")");
  if (q.reduction == Reduction::Crossing) {
    q.crossing_value = number_at(s, required(s, j, path, "crossing"), path + "/crossing");
    compared = 1;
  } else if (j.contains("crossing")) {
    fail(s, path + "/crossing", "only used with \"reduce\": \"crossing\"");
  }
  if (j.contains("relative")) {
    const json& r = j.at("relative");
    if (r.is_boolean()) q.normalization = r.get<bool>() ? Normalization::Reference : Normalization::None;
    else {
      const std::string n = string_at(s, r, path + "/relative");
      if (n == "reference") q.normalization = Normalization::Reference;
      else if (n == "initial") q.normalization = Normalization::Initial;
      else fail(s, path + "/relative", "expected true, false, \"reference\" or \"initial\"");
    }
  }
  if (j.contains("window")) {
    const json& w = j.at("window");
    if (!w.is_array() || w.size() != 2) fail(s, path + "/window", "expected [from, until] (s)");
    q.from = number_at(s, w[0], path + "/window/0");
    q.until = number_at(s, w[1], path + "/window/1");
    if (!(q.from < q.until)) fail(s, path + "/window", "expected from < until");
  }
  if (j.contains("expected_order")) q.expected_order = parse_expected(s, j.at("expected_order"), path + "/expected_order");
  if (j.contains("unit")) q.unit = string_at(s, j.at("unit"), path + "/unit");
  q.reference = parse_reference(s, required(s, j, path, "reference"), path + "/reference", compared);
  q.displacement = displacement;
  return q;
}

}  // namespace

int field_size(Field field) {
  switch (field) {
    case Field::Affine: return 9;
    case Field::KineticEnergy: return 1;
    default: return 3;
  }
}

StudySpec load_study(const std::filesystem::path& file) {
  StudySpec s;
  s.file = file;
  s.name = file.stem().string();
  std::ifstream in(file);
  if (!in) fail(s, "", "cannot open the study file");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    fail(s, "", std::string("not valid JSON: ") + e.what());
  }
  check_keys(s, j, "", {"description", "scene", "set", "sweep", "x", "constants", "quantities", "expected_order",
                        "check_intersections"});
  if (j.contains("description")) s.description = string_at(s, j.at("description"), "/description");
  const std::string scene = string_at(s, required(s, j, "", "scene"), "/scene");
  s.scene = std::filesystem::absolute(file.parent_path() / scene).lexically_normal();
  if (!std::filesystem::is_regular_file(s.scene))
    fail(s, "/scene", "base scene '" + s.scene.string() + "' does not exist (paths are relative to the study file)");
  if (j.contains("set")) {
    check_pointer_object(s, j.at("set"), "/set");
    s.set = j.at("set");
  }
  if (j.contains("constants")) {
    const json& c = j.at("constants");
    if (!c.is_object()) fail(s, "/constants", "expected an object of name → number");
    for (const auto& [key, value] : c.items()) s.constants[key] = number_at(s, value, "/constants/" + key);
  }
  const json& sweep = required(s, j, "", "sweep");
  if (!sweep.is_array() || sweep.empty()) fail(s, "/sweep", "expected a non-empty array of {path, values}");
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const std::string path = "/sweep/" + std::to_string(i);
    check_keys(s, sweep[i], path, {"path", "values", "label", "name"});
    SweepParameter p;
    p.path = string_at(s, required(s, sweep[i], path, "path"), path + "/path");
    if (p.path.empty() || p.path[0] != '/') fail(s, path + "/path", "expected a JSON pointer into the scene, e.g. \"/time/dt\"");
    const json& values = required(s, sweep[i], path, "values");
    if (!values.is_array() || values.empty()) fail(s, path + "/values", "expected a non-empty array");
    for (const json& v : values) p.values.push_back(v);
    if (sweep[i].contains("name")) p.name = string_at(s, sweep[i].at("name"), path + "/name");
    p.label = sweep[i].contains("label") ? string_at(s, sweep[i].at("label"), path + "/label") : p.path;
    for (const SweepParameter& other : s.sweep)
      if (other.path == p.path) fail(s, path + "/path", "'" + p.path + "' is swept twice");
    s.sweep.push_back(std::move(p));
  }
  s.x = -1;
  if (j.contains("x")) {
    const std::string x = string_at(s, j.at("x"), "/x");
    for (std::size_t i = 0; i < s.sweep.size(); ++i)
      if (s.sweep[i].path == x) s.x = int(i);
    if (s.x < 0) fail(s, "/x", "'" + x + "' is not one of the swept paths");
  } else {
    s.x = 0;
  }
  for (std::size_t i = 0; i < s.sweep[s.x].values.size(); ++i)
    if (!s.sweep[s.x].values[i].is_number() || !(s.sweep[s.x].values[i].get<double>() > 0))
      fail(s, "/sweep/" + std::to_string(s.x) + "/values/" + std::to_string(i),
           "the x-axis parameter takes positive numbers (log-log axes), got " + s.sweep[s.x].values[i].dump());
  const json& quantities = required(s, j, "", "quantities");
  if (!quantities.is_array() || quantities.empty()) fail(s, "/quantities", "expected a non-empty array");
  for (std::size_t i = 0; i < quantities.size(); ++i)
    s.quantities.push_back(parse_quantity(s, quantities[i], "/quantities/" + std::to_string(i)));
  if (j.contains("expected_order")) s.expected_order = parse_expected(s, j.at("expected_order"), "/expected_order");
  if (j.contains("check_intersections")) {
    if (!j.at("check_intersections").is_boolean()) fail(s, "/check_intersections", "expected true or false");
    s.check_intersections = j.at("check_intersections").get<bool>();
  }
  return s;
}

}  // namespace stiffsoft::study
