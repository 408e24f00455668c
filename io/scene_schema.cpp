#include "io/scene_schema.hpp"

#include <algorithm>
#include <cctype>
#include <iomanip>
#include <sstream>
#include <vector>

namespace stiffsoft {

namespace {

// The one schema. Every key a scene may hold is listed here, and only here; the loader,
// the default filling, the unknown-key errors and docs/scenes.md all read this text.
constexpr const char* kSchemaText = R"JSON([
  {"pointer": "/", "type": "object",
   "doc": "A scene: settings plus the list of bodies. SI units, y is up."},
  {"pointer": "/description", "type": "string", "required": true,
   "doc": "What the scene shows and how to run it (`stiffsoft run scenes/X.json -o out/X`)."},

  {"pointer": "/time", "type": "object", "doc": "Time stepping."},
  {"pointer": "/time/dt", "type": "number", "default": 0.01, "exclusive_min": 0, "unit": "s",
   "doc": "Time step h."},
  {"pointer": "/time/duration", "type": "number", "default": 1.0, "exclusive_min": 0, "unit": "s",
   "doc": "Simulated time."},
  {"pointer": "/time/integrator", "type": "string", "default": "backward_euler",
   "options": ["backward_euler", "bdf2"],
   "doc": "Time integrator of the incremental potential: backward Euler (dissipative) or BDF-2 (keeps far more energy, e.g. bounces)."},

  {"pointer": "/gravity", "type": "vector3", "default": [0.0, -9.81, 0.0], "unit": "m/s²",
   "doc": "Gravitational acceleration."},

  {"pointer": "/contact", "type": "object", "doc": "IPC barrier and friction."},
  {"pointer": "/contact/dhat", "type": "number", "default": null, "exclusive_min": 0, "unit": "m",
   "default_doc": "1e-3 × bounding-box diagonal",
   "doc": "Barrier activation distance d̂: surfaces closer than this repel. Initial gaps should be larger."},
  {"pointer": "/contact/mu", "type": "number", "default": 0.0, "min": 0,
   "doc": "Coulomb friction coefficient μ; 0 turns friction off."},
  {"pointer": "/contact/eps_v", "type": "number", "default": null, "exclusive_min": 0, "unit": "m/s",
   "default_doc": "1e-3 × bounding-box diagonal / s",
   "doc": "Static/kinetic friction smoothing speed ε_v: slower sliding counts as sticking."},
  {"pointer": "/contact/kappa", "type": "number", "default": null, "exclusive_min": 0, "unit": "Pa·m",
   "default_doc": "adaptive (IPC's rule)",
   "doc": "Fixed barrier stiffness κ; leave unset for IPC's adaptive stiffness."},
  {"pointer": "/contact/damping", "type": "number", "default": 0.0, "min": 0, "unit": "s",
   "doc": "Lagged Rayleigh damping k_d of contacts: damping force −k_d ∇²B(xⁿ) v with B the barrier energy at the step's start (Chen, Li et al. 2022); 0 turns it off. Lowers the bounce (see docs/joints.md)."},
  {"pointer": "/contact/pairs", "type": "list", "default": [],
   "doc": "Settings for the contacts between two named bodies, replacing the scene-wide ones for that pair (each pair at most once)."},
  {"pointer": "/contact/pairs/*", "type": "object", "doc": "One body pair."},
  {"pointer": "/contact/pairs/*/body_a", "type": "string", "required": true, "doc": "Name of a body."},
  {"pointer": "/contact/pairs/*/body_b", "type": "string", "required": true,
   "doc": "Name of a body; the same as body_a for a soft body's self-contact."},
  {"pointer": "/contact/pairs/*/damping", "type": "number", "default": 0.0, "min": 0, "unit": "s",
   "doc": "Lagged Rayleigh damping k_d of this pair's contacts (as contact.damping)."},

  {"pointer": "/solver", "type": "object", "doc": "Newton's stopping rule and the linear solver."},
  {"pointer": "/solver/tolerance", "type": "number", "default": null, "exclusive_min": 0, "unit": "m/s",
   "default_doc": "1e-2 × bounding-box diagonal / s",
   "doc": "Newton stops when the largest surface-point step divided by h is below this speed (ε_d)."},
  {"pointer": "/solver/max_iterations", "type": "integer", "default": 200, "min": 1,
   "doc": "Newton iteration cap per time step."},
  {"pointer": "/solver/linear", "type": "string", "default": "auto",
   "doc": "Linear solver backend: cholmod (supernodal Cholesky), petsc (CG + ICC(0)), petsc:KSP[:PC] with KSP in cg, minres, gmres and PC in none, jacobi, pbjacobi, vpbjacobi, icc, gamg, hypre (e.g. petsc:cg:gamg), or auto: CHOLMOD while its factorisation is predicted to cost at most 2 Mflop, PETSc CG + ICC(0) above (see docs/linear_solvers.md). PETSc options on the command line (-ksp_type, -pc_type, ...) apply on top."},
  {"pointer": "/solver/krylov_rtol_max", "type": "number", "default": 0.001, "exclusive_min": 0, "exclusive_max": 1,
   "doc": "Inexact Newton: each Krylov solve stops at the relative residual η given by Eisenstat–Walker's forcing terms, capped by this η_max (see docs/linear_solvers.md); CHOLMOD ignores it."},

  {"pointer": "/output", "type": "object", "doc": "What is written and how often."},
  {"pointer": "/output/frame_dt", "type": "number", "default": null, "exclusive_min": 0, "unit": "s",
   "default_doc": "max(dt, 1/60 s)",
   "doc": "Time between written frames."},

  {"pointer": "/bodies", "type": "list", "required": true, "min_length": 1,
   "doc": "The bodies of the scene."},
  {"pointer": "/bodies/*", "type": "object", "doc": "One body."},
  {"pointer": "/bodies/*/name", "type": "string", "required": true,
   "doc": "Unique, non-empty name; the ParaView block name."},
  {"pointer": "/bodies/*/kind", "type": "string", "default": "dynamic",
   "options": ["dynamic", "fixed", "kinematic"],
   "doc": "dynamic: moves under forces, as an affine or soft body (see model); fixed: static obstacle; kinematic: rigid, moves with the prescribed velocity and angular_velocity."},
  {"pointer": "/bodies/*/model", "type": "string", "default": "affine",
   "options": ["affine", "soft", "auto"],
   "doc": "How a dynamic body is discretised: affine (one stiff element, 12 DOFs), soft (tetrahedral FEM meshed by gmsh), or auto: affine when the material's strain under the scene's loads stays below 1e-3 (see docs/soft_bodies.md), soft otherwise; the choice is logged."},
  {"pointer": "/bodies/*/mesh", "type": "file", "required": true,
   "extensions": [".obj", ".stl", ".msh", ".step", ".stp", ".brep", ".geo"],
   "doc": "A mesh or geometry file, relative to the scene file's folder: a closed triangle surface (.obj, .stl), a gmsh tet mesh (.msh), CAD (.step, .stp, .brep) or a gmsh script (.geo). Soft bodies are tet-meshed from it; affine bodies use its surface."},
  {"pointer": "/bodies/*/mesh", "type": "object", "required": true,
   "doc": "A primitive shape centred at the origin, axis of symmetry along y."},
  {"pointer": "/bodies/*/mesh/primitive", "type": "string", "required": true,
   "options": ["box", "sphere", "cylinder", "torus", "plane"],
   "doc": "Which shape."},
  {"pointer": "/bodies/*/mesh/size", "type": "vector3", "default": [1.0, 1.0, 1.0], "exclusive_min": 0,
   "unit": "m", "when": {"primitive": ["box", "plane"]},
   "doc": "box: edge lengths along x, y, z; plane: size along x, thickness along y, size along z."},
  {"pointer": "/bodies/*/mesh/radius", "type": "number", "default": 0.5, "exclusive_min": 0,
   "unit": "m", "when": {"primitive": ["sphere", "cylinder", "torus"]},
   "doc": "Sphere and cylinder radius; torus major (centre-line) radius."},
  {"pointer": "/bodies/*/mesh/minor_radius", "type": "number", "default": 0.1, "exclusive_min": 0,
   "unit": "m", "when": {"primitive": ["torus"]},
   "doc": "Torus tube radius, < radius."},
  {"pointer": "/bodies/*/mesh/height", "type": "number", "default": 1.0, "exclusive_min": 0,
   "unit": "m", "when": {"primitive": ["cylinder"]},
   "doc": "Cylinder height along y."},
  {"pointer": "/bodies/*/mesh/resolution", "type": "integer", "default": 16, "min": 3,
   "when": {"primitive": ["sphere", "cylinder", "torus"]},
   "doc": "Segments around a circle (sphere: around the equator; torus: around both circles)."},
  {"pointer": "/bodies/*/density", "type": "number", "default": 1000.0, "exclusive_min": 0,
   "unit": "kg/m³", "doc": "Mass density (unused by fixed and kinematic bodies)."},
  {"pointer": "/bodies/*/material", "type": "object", "when": {"model": ["soft", "auto"]},
   "doc": "Elastic material of a soft body (and of an auto body, for the choice)."},
  {"pointer": "/bodies/*/material/model", "type": "string", "default": "stable_neo_hookean",
   "options": ["linear", "fixed_corotated", "stable_neo_hookean"],
   "doc": "Constitutive model: linear elasticity (small strain only), fixed corotated (Stomakhin et al. 2012) or stable neo-Hookean (Smith et al. 2018; survives inversion)."},
  {"pointer": "/bodies/*/material/young", "type": "number", "default": 1e6, "exclusive_min": 0, "unit": "Pa",
   "doc": "Young's modulus E."},
  {"pointer": "/bodies/*/material/poisson", "type": "number", "default": 0.4, "exclusive_min": -1, "exclusive_max": 0.5,
   "doc": "Poisson ratio ν; 0.5 (incompressible) would make λ infinite."},
  {"pointer": "/bodies/*/mesh_size", "type": "number", "default": null, "exclusive_min": 0, "unit": "m",
   "default_doc": "1/8 of the body's bounding-box diagonal", "when": {"model": ["soft", "auto"]},
   "doc": "Target tetrahedron edge length h for gmsh (unused for .msh files). Meshes are cached by content in $STIFFSOFT_MESH_CACHE or ~/.cache/stiffsoft/meshes."},
  {"pointer": "/bodies/*/dirichlet", "type": "list", "default": [], "when": {"model": ["soft", "auto"]},
   "doc": "Dirichlet conditions on a soft body's nodes (positions in the world frame, after placement). Each must select at least one node."},
  {"pointer": "/bodies/*/dirichlet/*", "type": "object", "doc": "One Dirichlet condition."},
  {"pointer": "/bodies/*/dirichlet/*/select", "type": "string", "required": true,
   "options": ["box", "half_space", "node_set"],
   "doc": "box: nodes inside [min, max]; half_space: nodes with (x − point)·normal ≥ 0; node_set: a named node set (physical group) of a .msh or .geo file."},
  {"pointer": "/bodies/*/dirichlet/*/min", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m",
   "when": {"select": ["box"]}, "doc": "Lower corner of the box."},
  {"pointer": "/bodies/*/dirichlet/*/max", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m",
   "when": {"select": ["box"]}, "doc": "Upper corner of the box."},
  {"pointer": "/bodies/*/dirichlet/*/point", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m",
   "when": {"select": ["half_space"]}, "doc": "A point on the bounding plane."},
  {"pointer": "/bodies/*/dirichlet/*/normal", "type": "vector3", "default": [0.0, -1.0, 0.0],
   "when": {"select": ["half_space"]}, "doc": "Direction into the selected side (need not be unit length)."},
  {"pointer": "/bodies/*/dirichlet/*/node_set", "type": "string", "default": "",
   "when": {"select": ["node_set"]}, "doc": "Name of the node set."},
  {"pointer": "/bodies/*/dirichlet/*/velocity", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m/s",
   "doc": "Prescribed velocity of the selected nodes: zero holds them fixed, otherwise they move at this velocity (followed through a stiff pull, like kinematic bodies)."},
  {"pointer": "/bodies/*/kappa", "type": "number", "default": 1e8, "exclusive_min": 0,
   "unit": "Pa", "doc": "Orthogonality stiffness κ of the affine body; rigidity error ≈ stress / κ."},
  {"pointer": "/bodies/*/position", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m",
   "doc": "Where the mesh's origin goes."},
  {"pointer": "/bodies/*/rotation_deg", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "°",
   "doc": "XYZ Euler angles, R = Rz·Ry·Rx (x applied first)."},
  {"pointer": "/bodies/*/scale", "type": "vector3", "default": [1.0, 1.0, 1.0], "exclusive_min": 0,
   "doc": "Per-axis scale, applied before the rotation."},
  {"pointer": "/bodies/*/velocity", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m/s",
   "doc": "Initial (kinematic: prescribed) linear velocity of the centre of mass."},
  {"pointer": "/bodies/*/angular_velocity", "type": "vector3", "default": [0.0, 0.0, 0.0],
   "unit": "rad/s", "doc": "Initial (kinematic: prescribed) angular velocity, world frame."},
  {"pointer": "/bodies/*/path", "type": "list", "default": [], "when": {"kind": ["kinematic"]},
   "doc": "Legs of constant velocity a kinematic body follows first, in order; after the last it moves with velocity and angular_velocity (e.g. press, then release)."},
  {"pointer": "/bodies/*/path/*", "type": "object", "doc": "One leg of a kinematic path."},
  {"pointer": "/bodies/*/path/*/duration", "type": "number", "required": true, "exclusive_min": 0, "unit": "s",
   "doc": "How long the leg lasts."},
  {"pointer": "/bodies/*/path/*/velocity", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "m/s",
   "doc": "Linear velocity of the centre of mass during the leg."},
  {"pointer": "/bodies/*/path/*/angular_velocity", "type": "vector3", "default": [0.0, 0.0, 0.0], "unit": "rad/s",
   "doc": "Angular velocity (world frame) during the leg."},

  {"pointer": "/joints", "type": "list", "default": [],
   "doc": "Joints between an affine body and another body or the world (docs/joints.md). Points and axes are world coordinates at the initial pose."},
  {"pointer": "/joints/*", "type": "object", "doc": "One joint."},
  {"pointer": "/joints/*/name", "type": "string", "required": true, "doc": "Unique, non-empty name."},
  {"pointer": "/joints/*/kind", "type": "string", "required": true,
   "options": ["ball", "hinge", "prismatic", "distance", "bounded_distance", "cone_twist"],
   "doc": "ball: a point of body_a stays on a point of body_b (exact); hinge: rotation about axis only (exact), with an optional rotation range; prismatic: sliding along axis only (orientation exact, off-axis drift by a stiff penalty), with an optional sliding range; distance: the anchors keep their initial distance (stiff penalty); bounded_distance: lower ≤ distance ≤ upper (barriers, never violated); cone_twist: a ball joint (exact) whose axis, carried by both bodies, bends at most swing and twists within twist_lower…twist_upper (barriers, never violated)."},
  {"pointer": "/joints/*/body_a", "type": "string", "required": true,
   "doc": "Name of an affine body (dynamic or kinematic)."},
  {"pointer": "/joints/*/body_b", "type": "string", "default": "world",
   "doc": "Name of the other body, or world. A soft body_b takes ball joints only, at its node nearest to anchor (and every node within nodes_within of it)."},
  {"pointer": "/joints/*/anchor", "type": "vector3", "required": true, "unit": "m",
   "doc": "The joint's point on body_a (and, for ball, cone_twist, hinge and prismatic joints, on body_b)."},
  {"pointer": "/joints/*/anchor_b", "type": "vector3", "default": null, "unit": "m",
   "default_doc": "required", "when": {"kind": ["distance", "bounded_distance"]},
   "doc": "The point on body_b whose distance to anchor is kept or bounded."},
  {"pointer": "/joints/*/axis", "type": "vector3", "default": [0.0, 0.0, 1.0],
   "when": {"kind": ["hinge", "prismatic", "cone_twist"]},
   "doc": "Hinge axis through anchor, sliding direction, or the cone-twist axis carried by both bodies (need not be unit length)."},
  {"pointer": "/joints/*/stiffness", "type": "number", "default": 1e6, "exclusive_min": 0, "unit": "N/m",
   "when": {"kind": ["prismatic", "distance"]},
   "doc": "Penalty stiffness k of the nonlinear equality: ½ k (length − rest)² or ½ k (off-axis distance)²."},
  {"pointer": "/joints/*/lower", "type": "number", "default": null, "unit": "rad or m",
   "default_doc": "no limit", "when": {"kind": ["hinge", "prismatic", "bounded_distance"]},
   "doc": "Lower limit: hinge angle (rad, > −π, < 0: the initial pose is angle 0), slide along axis (m, < 0) or distance (m, < initial distance)."},
  {"pointer": "/joints/*/upper", "type": "number", "default": null, "unit": "rad or m",
   "default_doc": "no limit", "when": {"kind": ["hinge", "prismatic", "bounded_distance"]},
   "doc": "Upper limit: hinge angle (rad, < π, > 0), slide (m, > 0) or distance (m, > initial distance)."},
  {"pointer": "/joints/*/swing", "type": "number", "default": null, "unit": "rad",
   "default_doc": "no limit", "when": {"kind": ["cone_twist"]},
   "doc": "Largest bend of body_a's axis away from body_b's (> 0, < π: the initial pose is bend 0); a barrier, never exceeded."},
  {"pointer": "/joints/*/twist_lower", "type": "number", "default": null, "unit": "rad",
   "default_doc": "no limit", "when": {"kind": ["cone_twist"]},
   "doc": "Lowest twist of body_a about the axis relative to body_b (< 0, > −π: the initial pose is twist 0), the bend undone first (docs/joints.md). Needs swing."},
  {"pointer": "/joints/*/twist_upper", "type": "number", "default": null, "unit": "rad",
   "default_doc": "no limit", "when": {"kind": ["cone_twist"]},
   "doc": "Highest twist (> 0, < π). Needs swing."},
  {"pointer": "/joints/*/limit_stiffness", "type": "number", "default": null, "exclusive_min": 0, "unit": "J",
   "default_doc": "auto: m_a (|g| ℓ_a + ½ v_a²)", "when": {"kind": ["hinge", "prismatic", "bounded_distance", "cone_twist"]},
   "doc": "Stiffness κ of the limits' barrier κ b(gap/ĝ), b(x) = −(x − 1)² ln x (IPC's log barrier on the normalised gap). A limit is never crossed whatever κ; reaching it with kinetic energy E leaves a gap ≈ ĝ exp(−E/κ), so κ near the energies at play keeps the gap well-conditioned. The default is that energy scale for body_a (mass m_a, size ℓ_a = its bounding-box diagonal, initial speed v_a of its fastest point): lifting it by its own size plus its initial kinetic energy; 1 J when both are 0."},
  {"pointer": "/joints/*/limit_activation", "type": "number", "default": 0.05, "exclusive_min": 0, "unit": "rad or m",
   "when": {"kind": ["hinge", "prismatic", "bounded_distance", "cone_twist"]},
   "doc": "Activation gap ĝ of the limits' barrier: it pushes only closer than this to a limit."},
  {"pointer": "/joints/*/damping", "type": "number", "default": 0.0, "min": 0, "unit": "N·m·s/rad or N·s/m",
   "doc": "Lagged viscous damping c of the joint's free coordinate (hinge angle, slide, distance; ball and cone_twist: the two bodies' relative angular velocity ω, not with a soft body_b): dissipation ½ c ṡ² (or ½ c |ω|²) with the map from velocities frozen at the step's start."},
  {"pointer": "/joints/*/nodes_within", "type": "number", "default": null, "exclusive_min": 0, "unit": "m",
   "default_doc": "nearest node only", "when": {"kind": ["ball"]},
   "doc": "Ball joint to a soft body_b: pins every node of body_b within this distance of anchor to the point of body_a it starts at (3 exact rows per node), gluing body_a onto body_b."}
])JSON";

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

std::string join(const Json& list, const std::string& separator = ", ") {
  std::string out;
  for (const auto& item : list) {
    if (!out.empty()) out += separator;
    out += item.is_string() ? item.get<std::string>() : item.dump();
  }
  return out;
}

// Human name of an entry's type, for "must be ..." messages.
std::string type_phrase(const Json& entry) {
  const std::string type = entry.at("type");
  if (type == "object") return "an object";
  if (type == "list") return "a list";
  if (type == "number") return "a number";
  if (type == "integer") return "an integer";
  if (type == "string") return "a string";
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
      check_range(value, entry, path);
      return value;
    }
    if (type == "string") {
      if (entry.contains("options") &&
          std::find(entry["options"].begin(), entry["options"].end(), value) == entry["options"].end())
        fail(path, "unknown value " + value.dump() + " (allowed: " + join(entry["options"]) + ")");
      return value;
    }
    if (type == "file") return validate_file(value, entry, path);
    fail(path, "schema error: unknown type " + type);
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw SceneError(file_, path, what);
  }

  static std::vector<const Json*> entries_at(const std::string& pointer) {
    std::vector<const Json*> found;
    for (const auto& entry : scene_schema())
      if (entry.at("pointer") == pointer) found.push_back(&entry);
    return found;
  }

  // The schema entry for this value; where the schema gives alternatives, the one whose
  // type fits.
  const Json& pick_entry(const Json& value, const std::string& pointer, const std::string& path) const {
    const auto entries = entries_at(pointer);
    std::string expected;
    for (const Json* entry : entries) {
      if (type_matches(*entry, value)) return *entry;
      expected += (expected.empty() ? "" : " or ") + type_phrase(*entry);
    }
    fail(path, "must be " + expected + " (got " + shown(value) + ")");
  }

  void check_range(const Json& value, const Json& entry, const std::string& path) const {
    const double x = value.get<double>();
    if (entry.contains("exclusive_min") && !(x > entry["exclusive_min"].get<double>()))
      fail(path, "must be > " + entry["exclusive_min"].dump() + " (got " + value.dump() + ")");
    if (entry.contains("min") && !(x >= entry["min"].get<double>()))
      fail(path, "must be >= " + entry["min"].dump() + " (got " + value.dump() + ")");
    if (entry.contains("exclusive_max") && !(x < entry["exclusive_max"].get<double>()))
      fail(path, "must be < " + entry["exclusive_max"].dump() + " (got " + value.dump() + ")");
    if (entry.contains("max") && !(x <= entry["max"].get<double>()))
      fail(path, "must be <= " + entry["max"].dump() + " (got " + value.dump() + ")");
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
      fail(path, "unsupported mesh file extension \"" + extension + "\" (allowed: " + join(allowed) + ")");
    // Relative paths are relative to the scene file, so a scene folder can be moved whole.
    const std::filesystem::path resolved = std::filesystem::absolute(folder_ / given).lexically_normal();
    if (!std::filesystem::is_regular_file(resolved))
      fail(path, "mesh file not found: " + resolved.string() + " (relative paths are resolved against " +
                     "the scene file's folder)");
    return resolved.string();
  }

  // The ordered, de-duplicated direct children of an object entry.
  static std::vector<std::pair<std::string, const Json*>> children_of(const std::string& pointer) {
    std::vector<std::pair<std::string, const Json*>> children;
    const std::string prefix = pointer == "/" ? "/" : pointer + "/";
    for (const auto& entry : scene_schema()) {
      const std::string p = entry.at("pointer");
      if (p.size() <= prefix.size() || p.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string key = p.substr(prefix.size());
      if (key.find('/') != std::string::npos) continue;
      const bool seen = std::any_of(children.begin(), children.end(),
                                    [&](const auto& child) { return child.first == key; });
      if (!seen) children.emplace_back(key, &entry);
    }
    return children;
  }

  // Whether a `when` condition holds: the sibling's value (given or default) is listed.
  static bool condition_holds(const Json& entry, const Json& object, const std::string& pointer) {
    if (!entry.contains("when")) return true;
    for (const auto& [sibling, values] : entry["when"].items()) {
      Json sibling_value;
      if (object.contains(sibling)) {
        sibling_value = object[sibling];
      } else {
        for (const Json* e : entries_at(child_pointer(pointer, sibling)))
          if (e->contains("default")) sibling_value = (*e)["default"];
      }
      if (std::find(values.begin(), values.end(), sibling_value) == values.end()) return false;
    }
    return true;
  }

  Json validate_object(const Json& value, const Json& /*entry*/, const std::string& pointer,
                       const std::string& path) const {
    const auto children = children_of(pointer);
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
            condition = sibling + " is " + join(values, " or ") + " (it is " +
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
    for (const auto& option : entry["options"]) options += (options.empty() ? "" : ", ") + ("`" + option.get<std::string>() + "`");
    parts.push_back(options);
  }
  if (entry.contains("extensions")) parts.push_back(join(entry["extensions"]));
  if (entry.contains("min_length")) parts.push_back("at least " + entry["min_length"].dump() + " item(s)");
  if (entry.contains("when"))
    for (const auto& [sibling, values] : entry["when"].items())
      parts.push_back("only when " + sibling + " is " + join(values, ", "));
  std::string out;
  for (const auto& part : parts) out += (out.empty() ? "" : "; ") + part;
  return out;
}

}  // namespace

SceneError::SceneError(std::string file, std::string json_path, std::string expected)
    : std::runtime_error(file + ": " + (json_path.empty() ? std::string("(root)") : json_path) + ": " + expected),
      file_(std::move(file)),
      json_path_(json_path.empty() ? "(root)" : std::move(json_path)),
      expected_(std::move(expected)) {}

const nlohmann::ordered_json& scene_schema() {
  static const Json schema = Json::parse(kSchemaText);
  return schema;
}

nlohmann::ordered_json apply_scene_schema(const nlohmann::ordered_json& scene,
                                          const std::filesystem::path& scene_folder,
                                          const std::string& file_label) {
  return Validator(scene_folder, file_label).validate(scene, "/", "");
}

std::string schema_markdown() {
  std::string md;
  md += "# Scene files\n\n";
  md += "<!-- Generated from io/scene_schema.cpp by stiffsoft::schema_markdown(); do not edit by hand.\n";
  md += "     Regenerate with: STIFFSOFT_WRITE_DOCS=1 io_tests --gtest_filter='SceneSchema*' -->\n\n";
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
  md += "- Bodies must start separated by more than d̂ (no overlaps).\n\n";
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
