#include "io/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "coupling/linear_solver/linear_solver.hpp"

namespace stiffsoft {

namespace {

using Json = nlohmann::ordered_json;

Eigen::Vector3d vector3(const Json& value) {
  return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

std::optional<double> optional_number(const Json& value) {
  if (value.is_null()) return std::nullopt;
  return value.get<double>();
}

Integrator integrator_from(const std::string& name) {
  return name == "bdf2" ? Integrator::BDF2 : Integrator::BackwardEuler;
}

std::string integrator_name(Integrator integrator) {
  return integrator == Integrator::BDF2 ? "bdf2" : "backward_euler";
}

BodyKind kind_from(const std::string& name) {
  if (name == "fixed") return BodyKind::Fixed;
  if (name == "kinematic") return BodyKind::Kinematic;
  return BodyKind::Dynamic;
}

std::string kind_name(BodyKind kind) {
  switch (kind) {
    case BodyKind::Fixed: return "fixed";
    case BodyKind::Kinematic: return "kinematic";
    case BodyKind::Dynamic: break;
  }
  return "dynamic";
}

ModelChoice model_from(const std::string& name) {
  if (name == "soft") return ModelChoice::Soft;
  if (name == "auto") return ModelChoice::Auto;
  return ModelChoice::Affine;
}

std::string model_name(ModelChoice model) {
  switch (model) {
    case ModelChoice::Soft: return "soft";
    case ModelChoice::Auto: return "auto";
    case ModelChoice::Affine: break;
  }
  return "affine";
}

const char* const kSelectNames[] = {"box", "half_space", "node_set"};

DirichletDescription dirichlet_from(const Json& d) {
  DirichletDescription out;
  const std::string select = d.at("select").get<std::string>();
  out.select = select == "half_space" ? DirichletDescription::Select::HalfSpace
               : select == "node_set" ? DirichletDescription::Select::NodeSet
                                      : DirichletDescription::Select::Box;
  if (d.contains("min")) out.min = vector3(d["min"]);
  if (d.contains("max")) out.max = vector3(d["max"]);
  if (d.contains("point")) out.point = vector3(d["point"]);
  if (d.contains("normal")) out.normal = vector3(d["normal"]);
  if (d.contains("node_set")) out.node_set = d["node_set"].get<std::string>();
  out.velocity = vector3(d.at("velocity"));
  return out;
}

PrimitiveShape::Type primitive_from(const std::string& name) {
  if (name == "sphere") return PrimitiveShape::Type::Sphere;
  if (name == "cylinder") return PrimitiveShape::Type::Cylinder;
  if (name == "torus") return PrimitiveShape::Type::Torus;
  if (name == "plane") return PrimitiveShape::Type::Plane;
  return PrimitiveShape::Type::Box;
}

std::string primitive_name(PrimitiveShape::Type type) {
  switch (type) {
    case PrimitiveShape::Type::Sphere: return "sphere";
    case PrimitiveShape::Type::Cylinder: return "cylinder";
    case PrimitiveShape::Type::Torus: return "torus";
    case PrimitiveShape::Type::Plane: return "plane";
    case PrimitiveShape::Type::Box: break;
  }
  return "box";
}

// The filled JSON has passed the schema, so every key is present (or absent only where a
// primitive does not use it) and of the right type; this is plain conversion.
MeshDescription mesh_from(const Json& mesh) {
  MeshDescription out;
  if (mesh.is_string()) {
    out.file = mesh.get<std::string>();
    return out;
  }
  PrimitiveShape shape;
  shape.type = primitive_from(mesh.at("primitive").get<std::string>());
  if (mesh.contains("size")) shape.extents = vector3(mesh["size"]);
  if (mesh.contains("radius")) shape.radius = mesh["radius"].get<double>();
  if (mesh.contains("minor_radius")) shape.minor_radius = mesh["minor_radius"].get<double>();
  if (mesh.contains("height")) shape.height = mesh["height"].get<double>();
  if (mesh.contains("resolution")) shape.resolution = mesh["resolution"].get<int>();
  out.primitive = shape;
  return out;
}

const char* const kJointKindNames[] = {"ball", "hinge", "prismatic", "distance", "bounded_distance", "cone_twist"};

JointKind joint_kind_from(const std::string& name) {
  for (int k = 0; k < 6; ++k)
    if (name == kJointKindNames[k]) return JointKind(k);
  return JointKind::Ball;
}

JointDescription joint_from(const Json& j) {
  JointDescription out;
  out.name = j.at("name").get<std::string>();
  out.kind = joint_kind_from(j.at("kind").get<std::string>());
  out.body_a = j.at("body_a").get<std::string>();
  out.body_b = j.at("body_b").get<std::string>();
  out.anchor = vector3(j.at("anchor"));
  if (j.contains("anchor_b") && !j["anchor_b"].is_null()) out.anchor_b = vector3(j["anchor_b"]);
  if (j.contains("axis")) out.axis = vector3(j["axis"]);
  if (j.contains("stiffness")) out.stiffness = j["stiffness"].get<double>();
  if (j.contains("lower")) out.lower = optional_number(j["lower"]);
  if (j.contains("upper")) out.upper = optional_number(j["upper"]);
  if (j.contains("swing")) out.swing = optional_number(j["swing"]);
  if (j.contains("twist_lower")) out.twist_lower = optional_number(j["twist_lower"]);
  if (j.contains("twist_upper")) out.twist_upper = optional_number(j["twist_upper"]);
  if (j.contains("limit_stiffness")) out.limit_stiffness = optional_number(j["limit_stiffness"]);
  if (j.contains("limit_activation")) out.limit_activation = j["limit_activation"].get<double>();
  if (j.contains("damping")) out.damping = j["damping"].get<double>();
  if (j.contains("nodes_within")) out.nodes_within = optional_number(j["nodes_within"]);
  return out;
}

// Joints: unique names, existing and distinct bodies, usable axes and limits.
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

void check_joint_relations(const Json& scene, const std::string& file,
                           const std::unordered_map<std::string, std::size_t>& bodies) {
  std::unordered_map<std::string, std::size_t> first_use;
  const Json& joints = scene.at("joints");
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string at = "joints[" + std::to_string(i) + "]";
    const JointDescription j = joint_from(joints[i]);
    if (j.name.empty()) throw SceneError(file, at + ".name", "must not be empty");
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
      throw SceneError(file, at + ".anchor_b", "required for kind \"" + std::string(kJointKindNames[int(j.kind)]) + "\"");
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

// What a schema entry cannot express: relations between values.
void check_relations(const Json& scene, const std::string& file) {
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
    if (name.empty()) throw SceneError(file, at + ".name", "must not be empty");
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
  out.description = scene.at("description").get<std::string>();

  const Json& time = scene.at("time");
  out.time.dt = time.at("dt").get<double>();
  out.time.duration = time.at("duration").get<double>();
  out.time.integrator = integrator_from(time.at("integrator").get<std::string>());

  out.gravity = vector3(scene.at("gravity"));

  const Json& contact = scene.at("contact");
  out.contact.dhat = optional_number(contact.at("dhat"));
  out.contact.mu = contact.at("mu").get<double>();
  out.contact.eps_v = optional_number(contact.at("eps_v"));
  out.contact.kappa = optional_number(contact.at("kappa"));
  out.contact.damping = contact.at("damping").get<double>();
  for (const Json& pair : contact.at("pairs"))
    out.contact.pairs.push_back({pair.at("body_a").get<std::string>(), pair.at("body_b").get<std::string>(),
                                 pair.at("damping").get<double>()});

  const Json& solver = scene.at("solver");
  out.solver.tolerance = optional_number(solver.at("tolerance"));
  out.solver.max_iterations = solver.at("max_iterations").get<int>();
  out.solver.linear = solver.at("linear").get<std::string>();
  out.solver.krylov_rtol_max = solver.at("krylov_rtol_max").get<double>();

  out.output.frame_dt = optional_number(scene.at("output").at("frame_dt"));

  for (const Json& body : scene.at("bodies")) {
    BodyDescription b;
    b.name = body.at("name").get<std::string>();
    b.kind = kind_from(body.at("kind").get<std::string>());
    b.model = model_from(body.at("model").get<std::string>());
    b.mesh = mesh_from(body.at("mesh"));
    b.density = body.at("density").get<double>();
    if (body.contains("material")) {
      const Json& m = body["material"];
      b.material = {m.at("model").get<std::string>(), m.at("young").get<double>(), m.at("poisson").get<double>()};
    }
    if (body.contains("mesh_size")) b.mesh_size = optional_number(body["mesh_size"]);
    if (body.contains("dirichlet"))
      for (const Json& d : body["dirichlet"]) b.dirichlet.push_back(dirichlet_from(d));
    b.kappa = body.at("kappa").get<double>();
    b.position = vector3(body.at("position"));
    b.rotation_deg = vector3(body.at("rotation_deg"));
    b.scale = vector3(body.at("scale"));
    b.velocity = vector3(body.at("velocity"));
    b.angular_velocity = vector3(body.at("angular_velocity"));
    if (body.contains("path"))
      for (const Json& leg : body["path"])
        b.path.push_back({leg.at("duration").get<double>(), vector3(leg.at("velocity")),
                          vector3(leg.at("angular_velocity"))});
    out.bodies.push_back(std::move(b));
  }
  for (const Json& joint : scene.at("joints")) out.joints.push_back(joint_from(joint));
  return out;
}

// nlohmann reports the byte offset of a syntax error; people want line and column.
std::string syntax_location(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(text.size(), byte > 0 ? byte - 1 : 0);
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The part of nlohmann's message after its own location prefix.
std::string syntax_reason(const std::string& what) {
  const std::size_t column = what.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  return what;
}

Json vector_json(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json optional_json(const std::optional<double>& value) { return value ? Json(*value) : Json(nullptr); }

// The keys the schema allows for this primitive (its `when` conditions), so the
// resolved JSON never lists a key the loader would reject.
bool primitive_uses(const std::string& key, const std::string& primitive) {
  for (const auto& entry : scene_schema()) {
    if (entry.at("pointer") != "/bodies/*/mesh/" + key) continue;
    if (!entry.contains("when")) return true;
    const Json& values = entry["when"].at("primitive");
    return std::find(values.begin(), values.end(), primitive) != values.end();
  }
  return false;
}

}  // namespace

SceneDescription load_scene_from_string(const std::string& text, const std::filesystem::path& scene_folder,
                                        const std::string& file_label, const std::string& name) {
  Json parsed;
  try {
    parsed = Json::parse(text);
  } catch (const nlohmann::json::parse_error& error) {
    throw SceneError(file_label, syntax_location(text, error.byte), "invalid JSON: " + syntax_reason(error.what()));
  }
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
  // Built in schema order; nlohmann::json (the declared return type) then sorts the keys.
  Json out = Json::object();
  out["description"] = scene.description;
  out["time"] = {{"dt", scene.time.dt},
                 {"duration", scene.time.duration},
                 {"integrator", integrator_name(scene.time.integrator)}};
  out["gravity"] = vector_json(scene.gravity);
  out["contact"] = {{"dhat", optional_json(scene.contact.dhat)},
                    {"mu", scene.contact.mu},
                    {"eps_v", optional_json(scene.contact.eps_v)},
                    {"kappa", optional_json(scene.contact.kappa)},
                    {"damping", scene.contact.damping},
                    {"pairs", Json::array()}};
  for (const ContactPairDescription& pair : scene.contact.pairs)
    out["contact"]["pairs"].push_back({{"body_a", pair.body_a}, {"body_b", pair.body_b}, {"damping", pair.damping}});
  out["solver"] = {{"tolerance", optional_json(scene.solver.tolerance)},
                   {"max_iterations", scene.solver.max_iterations},
                   {"linear", scene.solver.linear},
                   {"krylov_rtol_max", scene.solver.krylov_rtol_max}};
  out["output"] = {{"frame_dt", optional_json(scene.output.frame_dt)}};
  out["bodies"] = Json::array();
  for (const BodyDescription& body : scene.bodies) {
    Json b = Json::object();
    b["name"] = body.name;
    b["kind"] = kind_name(body.kind);
    b["model"] = model_name(body.model);
    if (body.mesh.primitive) {
      const PrimitiveShape& shape = *body.mesh.primitive;
      const std::string primitive = primitive_name(shape.type);
      Json mesh = {{"primitive", primitive}};
      if (primitive_uses("size", primitive)) mesh["size"] = vector_json(shape.extents);
      if (primitive_uses("radius", primitive)) mesh["radius"] = shape.radius;
      if (primitive_uses("minor_radius", primitive)) mesh["minor_radius"] = shape.minor_radius;
      if (primitive_uses("height", primitive)) mesh["height"] = shape.height;
      if (primitive_uses("resolution", primitive)) mesh["resolution"] = shape.resolution;
      b["mesh"] = mesh;
    } else {
      b["mesh"] = body.mesh.file.string();
    }
    b["density"] = body.density;
    if (body.model != ModelChoice::Affine) {
      b["material"] = {{"model", body.material.model},
                       {"young", body.material.young},
                       {"poisson", body.material.poisson}};
      b["mesh_size"] = optional_json(body.mesh_size);
      Json list = Json::array();
      for (const DirichletDescription& d : body.dirichlet) {
        Json entry = {{"select", kSelectNames[int(d.select)]}};
        switch (d.select) {
          case DirichletDescription::Select::Box:
            entry["min"] = vector_json(d.min);
            entry["max"] = vector_json(d.max);
            break;
          case DirichletDescription::Select::HalfSpace:
            entry["point"] = vector_json(d.point);
            entry["normal"] = vector_json(d.normal);
            break;
          case DirichletDescription::Select::NodeSet: entry["node_set"] = d.node_set; break;
        }
        entry["velocity"] = vector_json(d.velocity);
        list.push_back(entry);
      }
      b["dirichlet"] = list;
    }
    b["kappa"] = body.kappa;
    b["position"] = vector_json(body.position);
    b["rotation_deg"] = vector_json(body.rotation_deg);
    b["scale"] = vector_json(body.scale);
    b["velocity"] = vector_json(body.velocity);
    b["angular_velocity"] = vector_json(body.angular_velocity);
    if (body.kind == BodyKind::Kinematic) {
      b["path"] = Json::array();
      for (const PathSegment& leg : body.path)
        b["path"].push_back({{"duration", leg.duration},
                             {"velocity", vector_json(leg.velocity)},
                             {"angular_velocity", vector_json(leg.angular_velocity)}});
    }
    out["bodies"].push_back(b);
  }
  out["joints"] = Json::array();
  for (const JointDescription& joint : scene.joints) {
    const JointKind k = joint.kind;
    const bool distance = k == JointKind::Distance || k == JointKind::BoundedDistance;
    const bool limited = k == JointKind::Hinge || k == JointKind::Prismatic || k == JointKind::BoundedDistance ||
                         k == JointKind::ConeTwist;
    Json j = {{"name", joint.name},
              {"kind", kJointKindNames[int(k)]},
              {"body_a", joint.body_a},
              {"body_b", joint.body_b},
              {"anchor", vector_json(joint.anchor)}};
    if (distance) j["anchor_b"] = joint.anchor_b ? vector_json(*joint.anchor_b) : Json(nullptr);
    if (k == JointKind::Hinge || k == JointKind::Prismatic || k == JointKind::ConeTwist) j["axis"] = vector_json(joint.axis);
    if (k == JointKind::Prismatic || k == JointKind::Distance) j["stiffness"] = joint.stiffness;
    if (k == JointKind::ConeTwist) {
      j["swing"] = optional_json(joint.swing);
      j["twist_lower"] = optional_json(joint.twist_lower);
      j["twist_upper"] = optional_json(joint.twist_upper);
    } else if (limited) {
      j["lower"] = optional_json(joint.lower);
      j["upper"] = optional_json(joint.upper);
    }
    if (limited) {
      j["limit_stiffness"] = optional_json(joint.limit_stiffness);
      j["limit_activation"] = joint.limit_activation;
    }
    j["damping"] = joint.damping;
    if (k == JointKind::Ball) j["nodes_within"] = optional_json(joint.nodes_within);
    out["joints"].push_back(j);
  }
  return nlohmann::json(out);
}

}  // namespace stiffsoft
