#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <stiffsoft/scene/scene_loader.hpp>

namespace stiffsoft {
namespace {

const std::filesystem::path kData = std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "tests/scene/data";

/// One broken scene and the exact `json path: message` start its error must carry.
struct BrokenCase {
  const char* file;
  const char* path_and_message;
};

// Every file in data/broken/ must be listed here (a test checks), with the JSON path the
// error must name and the beginning of what it must say.
const BrokenCase kBroken[] = {
    {"missing_description.json", "description: required key is missing"},
    {"missing_body_name.json", "bodies[1].name: required key is missing"},
    {"wrong_type_dt.json", "time.dt: must be a number (got string \"0.01\")"},
    {"negative_density.json", "bodies[3].density: must be > 0 (got -2)"},
    {"unknown_key.json", "bodies[1].frobnicate: unknown key (allowed: name, kind, model, mesh, density, material, "
                         "mesh_size, dirichlet, kappa, position, rotation_deg, scale, velocity, angular_velocity, path)"},
    {"poisson_half.json", "bodies[0].material.poisson: must be < 0.5 (got 0.5)"},
    {"material_on_affine_body.json", "bodies[0].material: only allowed when model is soft or auto"},
    {"unknown_top_level_key.json", "gravty: unknown key (allowed: description, time, gravity,"},
    {"unknown_integrator.json", "time.integrator: unknown value \"rk4\" (allowed: backward_euler, bdf2)"},
    {"unknown_body_kind.json", "bodies[0].kind: unknown value \"soft\" (allowed: dynamic, fixed, kinematic)"},
    {"missing_mesh_file.json", "bodies[0].mesh: mesh file not found: "},
    {"unsupported_mesh_extension.json", "bodies[0].mesh: unsupported mesh file extension \".ply\" (allowed: .obj, .stl, .msh, .step, .stp, .brep, .geo)"},
    {"bad_syntax.json", "line 5, column 3: invalid JSON: "},
    {"duplicate_body_names.json", "bodies[2].name: duplicate body name \"crate\" (also used by bodies[0])"},
    {"wrong_array_length.json", "bodies[0].position: must be an array of 3 numbers (got an array of 2)"},
    {"wrong_vector_element_type.json", "bodies[0].scale[1]: must be a number (got string \"a\")"},
    {"zero_scale.json", "bodies[0].scale[1]: must be > 0 (got 0)"},
    {"key_not_used_by_primitive.json", "bodies[0].mesh.radius: only allowed when primitive is sphere or cylinder or torus"},
    {"unknown_primitive.json", "bodies[0].mesh.primitive: unknown value \"cone\""},
    {"torus_minor_radius_too_big.json", "bodies[0].mesh.minor_radius: must be < radius"},
    {"empty_bodies.json", "bodies: must hold at least 1 item(s) (got 0)"},
    {"fractional_resolution.json", "bodies[0].mesh.resolution: must be an integer (got 8.5)"},
    {"negative_friction.json", "contact.mu: must be >= 0 (got -0.1)"},
    {"mesh_wrong_type.json", "bodies[0].mesh: must be a mesh file path (string) or an object (got 5)"},
    {"root_not_object.json", "(root): must be an object (got an array of 2)"},
    {"zero_max_iterations.json", "solver.max_iterations: must be >= 1 (got 0)"},
    {"zero_friction_iterations.json", "contact.friction_iterations: must be >= 1 (got 0)"},
    {"krylov_rtol_max_one.json", "solver.krylov_rtol_max: must be < 1 (got 1)"},
    {"empty_body_name.json", "bodies[0].name: must not be empty or only white space"},
    {"blank_body_name.json", "bodies[0].name: must not be empty or only white space"},
    {"unknown_linear_solver.json", "solver.linear: unknown linear solver 'magic' (available: cholmod, auto, petsc"},
    {"unknown_preconditioner.json", "solver.linear: PETSc backend: unknown preconditioner 'ilu' (available: none, jacobi"},
    {"contact_pair_unknown_body.json", "contact.pairs[0].body_b: no body is named \"floor\""},
    {"contact_pair_twice.json", "contact.pairs[1]: the pair \"a\", \"b\" is already given by contact.pairs[0]"},
};

TEST(SceneLoader, EveryBrokenSceneGivesASceneErrorNamingFileAndJsonPath) {
  for (const BrokenCase& c : kBroken) {
    const std::filesystem::path file = kData / "broken" / c.file;
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    try {
      load_scene(file);
      ADD_FAILURE() << c.file << ": loaded without error";
    } catch (const SceneError& error) {
      const std::string expected_start = file.string() + ": " + c.path_and_message;
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(expected_start, 0), 0u) << "got:      " << message << "\nexpected: " << expected_start;
      EXPECT_EQ(error.file(), file.string());
    }
  }
}

TEST(SceneLoader, EveryFileInTheBrokenFolderIsListedInTheTest) {
  std::set<std::string> listed;
  for (const BrokenCase& c : kBroken) listed.insert(c.file);
  for (const auto& entry : std::filesystem::directory_iterator(kData / "broken"))
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " has no expectation";
}

TEST(SceneLoader, UnknownKeyCloseToAKnownOneGetsASuggestion) {
  try {
    load_scene(kData / "broken" / "unknown_top_level_key.json");
    FAIL() << "loaded";
  } catch (const SceneError& error) {
    EXPECT_NE(std::string(error.what()).find("did you mean \"gravity\"?"), std::string::npos) << error.what();
  }
}

TEST(SceneLoader, MissingFileIsASceneError) {
  EXPECT_THROW(load_scene(kData / "no_such_scene.json"), SceneError);
}

TEST(SceneLoader, SceneErrorIsARuntimeError) {
  const SceneError error("a.json", "bodies[3].density", "must be > 0 (got -2)");
  const std::runtime_error& base = error;
  EXPECT_STREQ(base.what(), "a.json: bodies[3].density: must be > 0 (got -2)");
  EXPECT_EQ(error.json_path(), "bodies[3].density");
  EXPECT_EQ(error.expected(), "must be > 0 (got -2)");
}

TEST(SceneLoader, MissingMeshFileErrorShowsTheResolvedPath) {
  try {
    load_scene(kData / "broken" / "missing_mesh_file.json");
    FAIL() << "loaded";
  } catch (const SceneError& error) {
    const std::string resolved = (kData / "broken" / "meshes" / "does_not_exist.obj").lexically_normal().string();
    EXPECT_NE(std::string(error.what()).find(resolved), std::string::npos) << error.what();
  }
}

TEST(SceneLoader, AGoodSceneKeepsEveryValueItGives) {
  const SceneDescription s = load_scene(kData / "good" / "all_keys.json");
  EXPECT_EQ(s.name, "all_keys");
  EXPECT_EQ(s.description, "Every key set to a non-default value, for the round-trip test.");
  EXPECT_EQ(s.time.dt, 0.005);
  EXPECT_EQ(s.time.duration, 0.25);
  EXPECT_EQ(s.time.integrator, Integrator::BDF2);
  EXPECT_EQ(s.gravity, Eigen::Vector3d(0.5, -3.0, 0.25));
  EXPECT_EQ(s.contact.dhat, 0.002);
  EXPECT_EQ(s.contact.mu, 0.4);
  EXPECT_EQ(s.contact.eps_v, 0.0005);
  EXPECT_EQ(s.contact.kappa, 1000.0);
  EXPECT_EQ(s.contact.damping, 0.001);
  EXPECT_TRUE(s.contact.balance_kappa);
  EXPECT_EQ(s.contact.friction_iterations, 3);
  EXPECT_FALSE(s.contact.check_start_gaps);
  ASSERT_EQ(s.contact.pairs.size(), 1u);
  EXPECT_EQ(s.contact.pairs[0].body_a, "ball");
  EXPECT_EQ(s.contact.pairs[0].body_b, "floor");
  EXPECT_EQ(s.contact.pairs[0].damping, 0.002);
  EXPECT_EQ(s.solver.tolerance, 0.003);
  EXPECT_EQ(s.solver.gap_tolerance, 0.3);
  EXPECT_EQ(s.solver.max_iterations, 17);
  EXPECT_EQ(s.solver.barrier_hessian, contact::BarrierHessian::GaussNewton);
  EXPECT_EQ(s.solver.release_hessian, 0.8);
  EXPECT_FALSE(s.solver.geodesic_line_search);
  EXPECT_FALSE(s.solver.island_line_search);
  EXPECT_FALSE(s.solver.entering_springs);
  EXPECT_EQ(s.solver.linear, "cholmod");
  EXPECT_EQ(s.solver.krylov_rtol_max, 0.01);
  EXPECT_EQ(s.output.frame_dt, 0.05);
  ASSERT_EQ(s.bodies.size(), 7u);

  const BodyDescription& tet = s.bodies[0];
  EXPECT_EQ(tet.name, "tet");
  EXPECT_EQ(tet.kind, Motion::Dynamic);
  EXPECT_FALSE(tet.mesh.primitive.has_value());
  EXPECT_TRUE(tet.mesh.file.is_absolute());
  EXPECT_EQ(tet.mesh.file, (kData / "meshes" / "tet.obj").lexically_normal());
  EXPECT_EQ(tet.density, 2500.0);
  EXPECT_EQ(tet.kappa, 1e9);
  EXPECT_EQ(tet.position, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(tet.rotation_deg, Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(tet.scale, Eigen::Vector3d(2, 3, 4));
  EXPECT_EQ(tet.velocity, Eigen::Vector3d(-1, -2, -3));
  EXPECT_EQ(tet.angular_velocity, Eigen::Vector3d(0.1, 0.2, 0.3));

  const BodyDescription& floor = s.bodies[1];
  EXPECT_EQ(floor.kind, Motion::Fixed);
  ASSERT_TRUE(floor.mesh.primitive.has_value());
  EXPECT_EQ(floor.mesh.primitive->type, PrimitiveShape::Type::Plane);
  EXPECT_EQ(floor.mesh.primitive->extents, Eigen::Vector3d(4, 0.1, 5));

  const BodyDescription& ring = s.bodies[2];
  EXPECT_EQ(ring.kind, Motion::Kinematic);
  EXPECT_EQ(ring.mesh.primitive->type, PrimitiveShape::Type::Torus);
  EXPECT_EQ(ring.mesh.primitive->radius, 0.3);
  EXPECT_EQ(ring.mesh.primitive->minor_radius, 0.05);
  EXPECT_EQ(ring.mesh.primitive->resolution, 12);
  EXPECT_EQ(ring.angular_velocity, Eigen::Vector3d(0, 2, 0));
  ASSERT_EQ(ring.path.size(), 2u);
  EXPECT_EQ(ring.path[0].duration, 0.1);
  EXPECT_EQ(ring.path[0].velocity, Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(ring.path[1].angular_velocity, Eigen::Vector3d(1, 0, 0));

  EXPECT_EQ(s.bodies[3].mesh.primitive->type, PrimitiveShape::Type::Sphere);
  EXPECT_EQ(s.bodies[3].mesh.primitive->radius, 0.2);
  EXPECT_EQ(s.bodies[3].mesh.primitive->resolution, 10);
  EXPECT_EQ(s.bodies[4].mesh.primitive->type, PrimitiveShape::Type::Cylinder);
  EXPECT_EQ(s.bodies[4].mesh.primitive->height, 0.4);
  EXPECT_EQ(s.bodies[4].mesh.primitive->resolution, 9);
  EXPECT_EQ(s.bodies[5].mesh.primitive->type, PrimitiveShape::Type::Box);
  EXPECT_EQ(s.bodies[5].mesh.primitive->extents, Eigen::Vector3d(0.1, 0.2, 0.3));

  const BodyDescription& jelly = s.bodies[6];
  EXPECT_EQ(jelly.model, ModelChoice::Soft);
  EXPECT_EQ(jelly.material.model, "fixed_corotated");
  EXPECT_EQ(jelly.material.young, 5e5);
  EXPECT_EQ(jelly.material.poisson, 0.3);
  EXPECT_EQ(jelly.mesh_size, 0.05);
  ASSERT_EQ(jelly.dirichlet.size(), 3u);
  EXPECT_EQ(jelly.dirichlet[0].select, DirichletDescription::Select::Box);
  EXPECT_EQ(jelly.dirichlet[0].max, Eigen::Vector3d(7.2, -0.09, 0.2));
  EXPECT_EQ(jelly.dirichlet[1].select, DirichletDescription::Select::HalfSpace);
  EXPECT_EQ(jelly.dirichlet[1].normal, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(jelly.dirichlet[1].velocity, Eigen::Vector3d(0, 0.5, 0));
  EXPECT_EQ(jelly.dirichlet[2].select, DirichletDescription::Select::NodeSet);
  EXPECT_EQ(jelly.dirichlet[2].node_set, "top");
}

TEST(SceneLoader, DefaultsAreFilledFromTheSchema) {
  const SceneDescription s = load_scene(kData / "good" / "minimal.json");
  EXPECT_EQ(s.time.dt, 0.01);
  EXPECT_EQ(s.time.duration, 1.0);
  EXPECT_EQ(s.time.integrator, Integrator::BackwardEuler);
  EXPECT_EQ(s.gravity, Eigen::Vector3d(0.0, -9.81, 0.0));
  EXPECT_FALSE(s.contact.dhat.has_value());
  EXPECT_EQ(s.contact.mu, 0.0);
  EXPECT_FALSE(s.contact.eps_v.has_value());
  EXPECT_FALSE(s.contact.kappa.has_value());
  EXPECT_FALSE(s.solver.tolerance.has_value());
  EXPECT_EQ(s.solver.max_iterations, 200);
  EXPECT_EQ(s.solver.linear, "auto");
  EXPECT_EQ(s.solver.krylov_rtol_max, ForcingTermSettings{}.eta_max);  // the schema agrees with the code
  EXPECT_FALSE(s.output.frame_dt.has_value());
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodyDescription& b = s.bodies[0];
  EXPECT_EQ(b.kind, Motion::Dynamic);
  EXPECT_EQ(b.density, 1000.0);
  EXPECT_EQ(b.kappa, 1e8);
  EXPECT_EQ(b.position, Eigen::Vector3d::Zero());
  EXPECT_EQ(b.rotation_deg, Eigen::Vector3d::Zero());
  EXPECT_EQ(b.scale, Eigen::Vector3d::Ones());
  EXPECT_EQ(b.velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(b.angular_velocity, Eigen::Vector3d::Zero());
  ASSERT_TRUE(b.mesh.primitive.has_value());
  EXPECT_EQ(b.mesh.primitive->type, PrimitiveShape::Type::Box);
  EXPECT_EQ(b.mesh.primitive->extents, Eigen::Vector3d::Ones());
}

// Field-by-field equality, so a mismatch names the field.
void expect_same_scene(const SceneDescription& a, const SceneDescription& b) {
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.time.dt, b.time.dt);
  EXPECT_EQ(a.time.duration, b.time.duration);
  EXPECT_EQ(a.time.integrator, b.time.integrator);
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.contact.dhat, b.contact.dhat);
  EXPECT_EQ(a.contact.mu, b.contact.mu);
  EXPECT_EQ(a.contact.eps_v, b.contact.eps_v);
  EXPECT_EQ(a.contact.kappa, b.contact.kappa);
  EXPECT_EQ(a.solver.tolerance, b.solver.tolerance);
  EXPECT_EQ(a.solver.max_iterations, b.solver.max_iterations);
  EXPECT_EQ(a.solver.barrier_hessian, b.solver.barrier_hessian);
  EXPECT_EQ(a.solver.release_hessian, b.solver.release_hessian);
  EXPECT_EQ(a.solver.geodesic_line_search, b.solver.geodesic_line_search);
  EXPECT_EQ(a.solver.island_line_search, b.solver.island_line_search);
  EXPECT_EQ(a.solver.entering_springs, b.solver.entering_springs);
  EXPECT_EQ(a.solver.linear, b.solver.linear);
  EXPECT_EQ(a.solver.krylov_rtol_max, b.solver.krylov_rtol_max);
  EXPECT_EQ(a.output.frame_dt, b.output.frame_dt);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyDescription& x = a.bodies[i];
    const BodyDescription& y = b.bodies[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.model, y.model);
    EXPECT_EQ(x.material.model, y.material.model);
    EXPECT_EQ(x.material.young, y.material.young);
    EXPECT_EQ(x.material.poisson, y.material.poisson);
    EXPECT_EQ(x.mesh_size, y.mesh_size);
    ASSERT_EQ(x.dirichlet.size(), y.dirichlet.size());
    for (std::size_t j = 0; j < x.dirichlet.size(); ++j) {
      EXPECT_EQ(x.dirichlet[j].select, y.dirichlet[j].select);
      EXPECT_EQ(x.dirichlet[j].min, y.dirichlet[j].min);
      EXPECT_EQ(x.dirichlet[j].max, y.dirichlet[j].max);
      EXPECT_EQ(x.dirichlet[j].point, y.dirichlet[j].point);
      EXPECT_EQ(x.dirichlet[j].normal, y.dirichlet[j].normal);
      EXPECT_EQ(x.dirichlet[j].node_set, y.dirichlet[j].node_set);
      EXPECT_EQ(x.dirichlet[j].velocity, y.dirichlet[j].velocity);
    }
    EXPECT_EQ(x.mesh.file, y.mesh.file);
    ASSERT_EQ(x.mesh.primitive.has_value(), y.mesh.primitive.has_value());
    if (x.mesh.primitive) {
      EXPECT_EQ(x.mesh.primitive->type, y.mesh.primitive->type);
      EXPECT_EQ(x.mesh.primitive->extents, y.mesh.primitive->extents);
      EXPECT_EQ(x.mesh.primitive->radius, y.mesh.primitive->radius);
      EXPECT_EQ(x.mesh.primitive->minor_radius, y.mesh.primitive->minor_radius);
      EXPECT_EQ(x.mesh.primitive->height, y.mesh.primitive->height);
      EXPECT_EQ(x.mesh.primitive->resolution, y.mesh.primitive->resolution);
    }
    EXPECT_EQ(x.density, y.density);
    EXPECT_EQ(x.kappa, y.kappa);
    EXPECT_EQ(x.position, y.position);
    EXPECT_EQ(x.rotation_deg, y.rotation_deg);
    EXPECT_EQ(x.scale, y.scale);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.angular_velocity, y.angular_velocity);
    ASSERT_EQ(x.path.size(), y.path.size());
    for (std::size_t j = 0; j < x.path.size(); ++j) {
      EXPECT_EQ(x.path[j].duration, y.path[j].duration);
      EXPECT_EQ(x.path[j].velocity, y.path[j].velocity);
      EXPECT_EQ(x.path[j].angular_velocity, y.path[j].angular_velocity);
    }
  }
}

TEST(SceneLoader, ResolvedJsonLoadsBackToTheSameScene) {
  for (const char* name : {"all_keys.json", "minimal.json"}) {
    SCOPED_TRACE(name);
    const SceneDescription first = load_scene(kData / "good" / name);
    const nlohmann::json resolved = resolved_scene_json(first);
    const SceneDescription second = load_scene_from_string(resolved.dump(2), "/nonexistent-folder", "resolved", first.name);
    expect_same_scene(first, second);
    EXPECT_EQ(second.name, first.name);
  }
}

TEST(SceneLoader, ResolvedJsonWritesRelativeDefaultsAsNull) {
  const nlohmann::json resolved = resolved_scene_json(load_scene(kData / "good" / "minimal.json"));
  EXPECT_TRUE(resolved.at("contact").at("dhat").is_null());
  EXPECT_TRUE(resolved.at("contact").at("eps_v").is_null());
  EXPECT_TRUE(resolved.at("contact").at("kappa").is_null());
  EXPECT_TRUE(resolved.at("solver").at("tolerance").is_null());
  EXPECT_TRUE(resolved.at("output").at("frame_dt").is_null());
  EXPECT_EQ(resolved.at("time").at("integrator"), "backward_euler");
  EXPECT_EQ(resolved.at("solver").at("barrier_hessian"), "projected");
  EXPECT_EQ(resolved.at("bodies").at(0).at("mesh").at("size"), nlohmann::json::array({1.0, 1.0, 1.0}));
  EXPECT_FALSE(resolved.at("bodies").at(0).at("mesh").contains("radius"));
}

TEST(SceneLoader, SyntaxErrorLocationCountsLinesAndColumns) {
  try {
    load_scene_from_string("{\n  \"a\": 1,\n  \"b\" 2\n}\n", ".", "inline.json", "inline");
    FAIL() << "parsed";
  } catch (const SceneError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("inline.json: line 3, column 7: invalid JSON: ", 0), 0u) << error.what();
  }
}

}  // namespace
}  // namespace stiffsoft
