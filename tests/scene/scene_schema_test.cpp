#include <functional>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <stiffsoft/coupling/solver/newton.hpp>
#include <stiffsoft/meshing/primitive.hpp>
#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <stiffsoft/scene/scene_schema.hpp>
#include <stiffsoft/scene/schema_markdown.hpp>

namespace stiffsoft {
namespace {

const std::filesystem::path kSource(STIFFSOFT_SOURCE_DIR);

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

TEST(SceneSchema, DocsScenesMdIsTheRenderedSchema) {
  EXPECT_EQ(read_text(kSource / "docs" / "scenes.md"), schema_markdown())
      << "docs/scenes.md is out of date; regenerate it with "
         "`build/release/apps/stiffsoft schema --markdown > docs/scenes.md`";
}

TEST(SceneSchema, EveryEntryHasAKnownTypeAndADoc) {
  const std::set<std::string> types = {"object", "list", "number", "integer", "string", "boolean", "vector3", "file"};
  for (const auto& entry : scene_schema()) {
    SCOPED_TRACE(entry.dump());
    ASSERT_TRUE(entry.contains("pointer"));
    ASSERT_TRUE(entry.contains("type"));
    EXPECT_TRUE(types.count(entry["type"].get<std::string>()));
    ASSERT_TRUE(entry.contains("doc"));
    EXPECT_FALSE(entry["doc"].get<std::string>().empty());
    if (entry.contains("default") && entry["default"].is_null()) {
      EXPECT_TRUE(entry.contains("default_doc"));
    }
  }
}

TEST(SceneSchema, EveryDefaultPassesItsOwnEntry) {
  // A default that broke its own range would be written into every scene.
  for (const auto& entry : scene_schema()) {
    if (!entry.contains("default") || entry["default"].is_null()) continue;
    SCOPED_TRACE(entry.dump());
    const double lo_exclusive = entry.value("exclusive_min", -1e300);
    const double lo = entry.value("min", -1e300);
    const double hi_exclusive = entry.value("exclusive_max", 1e300);
    const double hi = entry.value("max", 1e300);
    const auto values = entry["default"].is_array() ? entry["default"] : nlohmann::ordered_json::array({entry["default"]});
    for (const auto& v : values) {
      if (!v.is_number()) continue;
      EXPECT_GT(v.get<double>(), lo_exclusive);
      EXPECT_GE(v.get<double>(), lo);
      EXPECT_LT(v.get<double>(), hi_exclusive);
      EXPECT_LE(v.get<double>(), hi);
    }
    if (entry.contains("options")) {
      const auto& options = entry["options"];
      EXPECT_NE(std::find(options.begin(), options.end(), entry["default"]), options.end());
    }
  }
}

TEST(SceneSchema, ResolvedJsonHasEveryKeyOfTheSchema) {
  // A scene whose bodies use every primitive; the resolved JSON must name every schema
  // pointer (primitive keys only where their `when` allows), so the writer cannot drift
  // from the schema.
  const SceneDescription scene =
      load_scene(kSource / "tests" / "scene" / "data" / "good" / "all_keys.json");
  const nlohmann::json resolved = resolved_scene_json(scene);
  for (const auto& entry : scene_schema()) {
    const std::string pointer = entry["pointer"];
    if (pointer == "/") continue;
    SCOPED_TRACE(pointer);
    // Replace each list wildcard by the index of an element (a body, a Dirichlet condition)
    // that uses the key.
    const std::function<bool(const std::string&)> found = [&](const std::string& concrete) {
      const std::size_t star = concrete.find('*');
      if (star == std::string::npos) return resolved.contains(nlohmann::json::json_pointer(concrete));
      const nlohmann::json::json_pointer list(concrete.substr(0, star - 1));
      if (!resolved.contains(list)) return false;
      for (std::size_t i = 0; i < resolved[list].size(); ++i)
        if (found(std::string(concrete).replace(star, 1, std::to_string(i)))) return true;
      return false;
    };
    EXPECT_TRUE(found(pointer)) << pointer << " is missing from resolved_scene_json";
  }
}

TEST(SceneSchema, MarkdownListsEveryKey) {
  const std::string md = schema_markdown();
  for (const char* key : {"`description`", "`time.dt`", "`contact.dhat`", "`bodies[].mesh.minor_radius`",
                          "`bodies[].angular_velocity`", "`solver.linear`", "`output.frame_dt`"})
    EXPECT_NE(md.find(key), std::string::npos) << key;
}

// The defaults a scene file gets for the keys it leaves out are those of the
// default-constructed description structs (scene_schema.cpp copies most of them from the
// structs; the enum defaults are still written in the schema text). The helpers below check,
// field by field, every field a test scene leaves unset.

void expect_default_time(const TimeDescription& time) {
  const TimeDescription d{};
  EXPECT_EQ(time.dt, d.dt);
  EXPECT_EQ(time.duration, d.duration);
  EXPECT_EQ(time.integrator, d.integrator);
}

void expect_default_contact(const ContactDescription& contact) {
  const ContactDescription d{};
  EXPECT_EQ(contact.dhat, d.dhat);
  EXPECT_EQ(contact.mu, d.mu);
  EXPECT_EQ(contact.eps_v, d.eps_v);
  EXPECT_EQ(contact.kappa, d.kappa);
  EXPECT_EQ(contact.damping, d.damping);
  EXPECT_EQ(contact.balance_kappa, d.balance_kappa);
  EXPECT_EQ(contact.friction_iterations, d.friction_iterations);
  EXPECT_EQ(contact.check_start_gaps, d.check_start_gaps);
}

void expect_default_solver(const SolverDescription& solver) {
  const SolverDescription d{};
  EXPECT_EQ(solver.tolerance, d.tolerance);
  EXPECT_EQ(solver.gap_tolerance, d.gap_tolerance);
  EXPECT_EQ(solver.max_iterations, d.max_iterations);
  EXPECT_EQ(solver.release_hessian, d.release_hessian);
  EXPECT_EQ(solver.geodesic_line_search, d.geodesic_line_search);
  EXPECT_EQ(solver.island_line_search, d.island_line_search);
  EXPECT_EQ(solver.entering_springs, d.entering_springs);
  EXPECT_EQ(solver.linear, d.linear);
  EXPECT_EQ(solver.krylov_rtol_max, d.krylov_rtol_max);
}

void expect_default_material(const SoftMaterial& material) {
  const SoftMaterial d{};
  EXPECT_EQ(material.model, d.model);
  EXPECT_EQ(material.young, d.young);
  EXPECT_EQ(material.poisson, d.poisson);
}

// Everything but name, kind, model and mesh (which a scene sets).
void expect_default_body_settings(const BodyDescription& body) {
  const BodyDescription d{};
  EXPECT_EQ(body.density, d.density);
  expect_default_material(body.material);
  EXPECT_EQ(body.mesh_size, d.mesh_size);
  EXPECT_TRUE(body.dirichlet.empty());
  EXPECT_EQ(body.kappa, d.kappa);
  EXPECT_EQ(body.position, d.position);
  EXPECT_EQ(body.rotation_deg, d.rotation_deg);
  EXPECT_EQ(body.scale, d.scale);
  EXPECT_EQ(body.velocity, d.velocity);
  EXPECT_EQ(body.angular_velocity, d.angular_velocity);
  EXPECT_TRUE(body.path.empty());
}

// Everything but the type.
void expect_default_primitive(const PrimitiveShape& shape) {
  const PrimitiveShape d{};
  EXPECT_EQ(shape.extents, d.extents);
  EXPECT_EQ(shape.radius, d.radius);
  EXPECT_EQ(shape.minor_radius, d.minor_radius);
  EXPECT_EQ(shape.height, d.height);
  EXPECT_EQ(shape.resolution, d.resolution);
}

// Everything but the selection rule.
void expect_default_dirichlet(const DirichletDescription& dirichlet) {
  const DirichletDescription d{};
  EXPECT_EQ(dirichlet.min, d.min);
  EXPECT_EQ(dirichlet.max, d.max);
  EXPECT_EQ(dirichlet.point, d.point);
  EXPECT_EQ(dirichlet.normal, d.normal);
  EXPECT_EQ(dirichlet.node_set, d.node_set);
  EXPECT_EQ(dirichlet.velocity, d.velocity);
}

// Everything but name, kind, body_a, anchor, and what a kind requires (anchor_b, a limit).
void expect_default_joint(const JointDescription& joint) {
  const JointDescription d{};
  EXPECT_EQ(joint.body_b, d.body_b);
  EXPECT_EQ(joint.axis, d.axis);
  EXPECT_EQ(joint.stiffness, d.stiffness);
  if (joint.kind != JointKind::BoundedDistance) {
    EXPECT_EQ(joint.lower, d.lower);
    EXPECT_EQ(joint.upper, d.upper);
  }
  EXPECT_EQ(joint.swing, d.swing);
  EXPECT_EQ(joint.twist_lower, d.twist_lower);
  EXPECT_EQ(joint.twist_upper, d.twist_upper);
  EXPECT_EQ(joint.limit_stiffness, d.limit_stiffness);
  EXPECT_EQ(joint.limit_activation, d.limit_activation);
  EXPECT_EQ(joint.damping, d.damping);
  EXPECT_EQ(joint.nodes_within, d.nodes_within);
}

TEST(SceneSchema, MinimalSceneGetsTheStructDefaults) {
  // Only description and one body's name and mesh are set: every other field is a default,
  // and the schema's must be the struct's.
  const SceneDescription scene = load_scene(kSource / "tests" / "scene" / "data" / "good" / "minimal.json");
  const SceneDescription d{};
  expect_default_time(scene.time);
  EXPECT_EQ(scene.gravity, d.gravity);
  expect_default_contact(scene.contact);
  EXPECT_TRUE(scene.contact.pairs.empty());
  expect_default_solver(scene.solver);
  EXPECT_EQ(scene.output.frame_dt, d.output.frame_dt);
  EXPECT_TRUE(scene.joints.empty());
  ASSERT_EQ(scene.bodies.size(), 1u);
  const BodyDescription& body = scene.bodies[0];
  EXPECT_EQ(body.kind, BodyDescription{}.kind);
  EXPECT_EQ(body.model, BodyDescription{}.model);
  expect_default_body_settings(body);
  ASSERT_TRUE(body.mesh.primitive.has_value());
  EXPECT_EQ(body.mesh.primitive->type, PrimitiveShape{}.type);
  expect_default_primitive(*body.mesh.primitive);
}

TEST(SceneSchema, EveryStructDefaultReachesTheScene) {
  // The keys the minimal scene cannot reach (they only apply to some primitives, soft
  // bodies, Dirichlet conditions, path legs, joints and contact pairs), each left unset.
  const std::string text = R"({
    "description": "Every list element with only its required keys.",
    "bodies": [
      {"name": "box", "mesh": {"primitive": "box"}},
      {"name": "sphere", "mesh": {"primitive": "sphere"}},
      {"name": "cylinder", "mesh": {"primitive": "cylinder"}},
      {"name": "torus", "mesh": {"primitive": "torus"}},
      {"name": "plane", "mesh": {"primitive": "plane"}},
      {"name": "soft", "model": "soft", "mesh": {"primitive": "box"},
       "dirichlet": [{"select": "box"}, {"select": "half_space"}, {"select": "node_set"}]},
      {"name": "auto", "model": "auto", "mesh": {"primitive": "box"}},
      {"name": "pusher", "kind": "kinematic", "mesh": {"primitive": "box"}, "path": [{"duration": 1}]}
    ],
    "contact": {"pairs": [{"body_a": "box", "body_b": "sphere"}]},
    "joints": [
      {"name": "ball", "kind": "ball", "body_a": "box", "anchor": [0, 0, 0]},
      {"name": "hinge", "kind": "hinge", "body_a": "box", "anchor": [0, 0, 0]},
      {"name": "prismatic", "kind": "prismatic", "body_a": "box", "anchor": [0, 0, 0]},
      {"name": "distance", "kind": "distance", "body_a": "box", "anchor": [0, 0, 0], "anchor_b": [1, 0, 0]},
      {"name": "bounded", "kind": "bounded_distance", "body_a": "box", "anchor": [0, 0, 0],
       "anchor_b": [1, 0, 0], "upper": 2},
      {"name": "cone", "kind": "cone_twist", "body_a": "box", "anchor": [0, 0, 0]}
    ]
  })";
  const SceneDescription scene = load_scene_from_string(text, kSource, "every_default.json", "every_default");
  expect_default_time(scene.time);
  expect_default_contact(scene.contact);
  expect_default_solver(scene.solver);
  ASSERT_EQ(scene.bodies.size(), 8u);
  for (const BodyDescription& body : scene.bodies) {
    SCOPED_TRACE(body.name);
    ASSERT_TRUE(body.mesh.primitive.has_value());
    expect_default_primitive(*body.mesh.primitive);
    if (body.name == "soft") {
      ASSERT_EQ(body.dirichlet.size(), 3u);
      for (const DirichletDescription& dirichlet : body.dirichlet) expect_default_dirichlet(dirichlet);
      BodyDescription without_dirichlet = body;
      without_dirichlet.dirichlet.clear();
      expect_default_body_settings(without_dirichlet);
    } else if (body.name == "pusher") {
      ASSERT_EQ(body.path.size(), 1u);
      EXPECT_EQ(body.path[0].velocity, PathSegment{}.velocity);
      EXPECT_EQ(body.path[0].angular_velocity, PathSegment{}.angular_velocity);
      BodyDescription without_path = body;
      without_path.path.clear();
      expect_default_body_settings(without_path);
    } else {
      expect_default_body_settings(body);
    }
  }
  ASSERT_EQ(scene.contact.pairs.size(), 1u);
  EXPECT_EQ(scene.contact.pairs[0].damping, ContactPairDescription{}.damping);
  ASSERT_EQ(scene.joints.size(), 6u);
  for (const JointDescription& joint : scene.joints) {
    SCOPED_TRACE(joint.name);
    expect_default_joint(joint);
  }
}

TEST(SceneSchema, StructDefaultsAreInTheSchemaWithTheirJsonType) {
  // Spot checks of the pointer → struct table: integers stay integers (the validator's
  // `integer` type), vectors are arrays, strings are strings.
  auto default_of = [](const std::string& pointer) {
    for (const auto& entry : scene_schema())
      if (entry.at("pointer") == pointer) return entry.at("default");
    ADD_FAILURE() << pointer << " not in the schema";
    return nlohmann::ordered_json();
  };
  EXPECT_TRUE(default_of("/solver/max_iterations").is_number_integer());
  EXPECT_EQ(default_of("/solver/max_iterations").get<int>(), SolverDescription{}.max_iterations);
  EXPECT_EQ(SolverDescription{}.max_iterations, NewtonSettings{}.max_iterations);
  EXPECT_TRUE(default_of("/bodies/*/mesh/resolution").is_number_integer());
  EXPECT_TRUE(default_of("/time/dt").is_number_float());
  EXPECT_EQ(default_of("/time/dt").get<double>(), TimeDescription{}.dt);
  EXPECT_EQ(default_of("/gravity"), nlohmann::ordered_json::array({0.0, -9.81, 0.0}));
  EXPECT_EQ(default_of("/joints/*/body_b").get<std::string>(), JointDescription{}.body_b);
  // Inserted where the text writes the other defaults: right after `type`.
  for (const auto& entry : scene_schema()) {
    if (!entry.contains("default")) continue;
    auto key = entry.items().begin();
    ASSERT_EQ((++key).key(), "type") << entry.dump();
    EXPECT_EQ((++key).key(), "default") << entry.dump();
  }
}

}  // namespace
}  // namespace stiffsoft
