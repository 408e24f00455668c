#include <stiffsoft/scene/scene_schema.hpp>

#include <algorithm>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include <stiffsoft/meshing/primitive.hpp>
#include <stiffsoft/scene/scene.hpp>
#include <stiffsoft/scene/scene_fields.hpp>

namespace stiffsoft {

namespace {

using Json = nlohmann::ordered_json;

// The one schema. Every key a scene may hold is listed here, and only here; the loader,
// the default filling, the unknown-key errors and docs/scenes.md all read this text.
// A default that a description struct holds (stiffsoft/scene/scene.hpp) is not written here
// but copied from the struct by struct_defaults() below, so each such number lives in one
// place. What stays here: defaults computed from the scene (null, with default_doc), empty
// lists, and the enum defaults (time.integrator, bodies[].kind, bodies[].model) whose names
// only the loader's private conversions know; a test (SceneSchema,
// MinimalSceneGetsTheStructDefaults) keeps those equal to the structs.
constexpr const char* kSchemaText = R"JSON([
  {"pointer": "/", "type": "object",
   "doc": "A scene: settings plus the list of bodies. SI units, y is up."},
  {"pointer": "/description", "type": "string", "required": true,
   "doc": "What the scene shows and how to run it (`stiffsoft run scenes/X.json -o out/X`)."},

  {"pointer": "/time", "type": "object", "doc": "Time stepping."},
  {"pointer": "/time/dt", "type": "number", "exclusive_min": 0, "unit": "s",
   "doc": "Time step h."},
  {"pointer": "/time/duration", "type": "number", "exclusive_min": 0, "unit": "s",
   "doc": "Simulated time."},
  {"pointer": "/time/integrator", "type": "string",
   "options": ["backward_euler", "bdf2"],
   "doc": "Time integrator of the incremental potential: backward Euler (dissipative) or BDF-2 (keeps far more energy, e.g. bounces)."},

  {"pointer": "/gravity", "type": "vector3", "min": -1000, "max": 1000, "unit": "m/s²",
   "doc": "Gravitational acceleration (each component within ±1000 m/s², about 100 g: more is most likely a unit slip, e.g. mm/s²)."},

  {"pointer": "/contact", "type": "object", "doc": "IPC barrier and friction."},
  {"pointer": "/contact/dhat", "type": "number", "default": null, "exclusive_min": 0, "unit": "m",
   "default_doc": "1e-3 × bounding-box diagonal, at most 1 % of the smallest body's",
   "doc": "Barrier activation distance d̂: surfaces closer than this repel. Bodies must start more than d̂ apart, and d̂ must be at most 1 % of every body's bounding-box diagonal (checked unless contact.check_start_gaps is false)."},
  {"pointer": "/contact/mu", "type": "number", "min": 0,
   "doc": "Coulomb friction coefficient μ; 0 turns friction off."},
  {"pointer": "/contact/eps_v", "type": "number", "default": null, "exclusive_min": 0, "unit": "m/s",
   "default_doc": "1e-3 × bounding-box diagonal / s",
   "doc": "Static/kinetic friction smoothing speed ε_v: slower sliding counts as sticking."},
  {"pointer": "/contact/kappa", "type": "number", "default": null, "exclusive_min": 0, "unit": "Pa·m",
   "default_doc": "adaptive (IPC's rule)",
   "doc": "Fixed barrier stiffness κ; leave unset for IPC's adaptive stiffness: κ_min (ipc-toolkit's initial stiffness for the scene's size and average mass), doubled when contacts come closer than 1e-9 × bounding-box diagonal."},
  {"pointer": "/contact/balance_kappa", "type": "boolean",
   "doc": "Adaptive κ only: at the first contact, set κ once to balance the other forces (IPC's initial-stiffness formula, within [κ_min, 100 κ_min]). For a scene that starts at rest in contact this keeps the contact's physical stiffness κ / (β h²) the same at every h, which convergence studies in h need (κ_min's is 4× stiffer when h halves; see docs/accuracy.md, incline). Contacts then rest nearer d̂, on the barrier's flat tail, which costs Newton iterations (medium pile at h = 1/240: 10.7 against 8.6 per step; see docs/newton.md)."},
  {"pointer": "/contact/friction_iterations", "type": "integer", "min": 1,
   "doc": "How many times friction's normal forces and tangent bases are lagged per step: at the step's start, then, while the result's lag error exceeds eps_v / 10 (stats.csv friction_lag_error: an estimate, per body, of the change of its mean velocity that friction with the normal forces at the result would make, from the change of their sum; force moving between a body's contacts is not seen), again at the result and the step solved again. Above 1, Newton also does not stop while its last direction moves a sticking contact (slip below eps_v h) by more than eps_v h / 10, whatever solver.tolerance: friction's velocities are resolved to eps_v / 10. 1 is IPC's lagged friction; more makes friction act in the step where a contact starts (a landing on an incline) and lets a block break loose from static friction within the step, at the price of iterations (see docs/newton.md)."},
  {"pointer": "/contact/damping", "type": "number", "min": 0, "unit": "s",
   "doc": "Lagged Rayleigh damping k_d of contacts: damping force −k_d ∇²B(xⁿ) v with B the barrier energy at the step's start (Chen, Li et al. 2022); 0 turns it off. Lowers the bounce (see docs/joints.md)."},
  {"pointer": "/contact/check_start_gaps", "type": "boolean",
   "doc": "Refuse the scene when two bodies start closer than d̂ (their closest surface points; the error names both bodies, the gap and a d̂ that fits) or when d̂ is above 1 % of a body's bounding-box diagonal (see docs/robustness.md). Turn it off only for bodies that start in contact on purpose, e.g. at the barrier's resting gap. A soft body's distance to itself is not checked."},
  {"pointer": "/contact/pairs", "type": "list", "default": [],
   "doc": "Settings for the contacts between two named bodies, replacing the scene-wide ones for that pair (each pair at most once)."},
  {"pointer": "/contact/pairs/*", "type": "object", "doc": "One body pair."},
  {"pointer": "/contact/pairs/*/body_a", "type": "string", "required": true, "doc": "Name of a body."},
  {"pointer": "/contact/pairs/*/body_b", "type": "string", "required": true,
   "doc": "Name of a body; the same as body_a for a soft body's self-contact."},
  {"pointer": "/contact/pairs/*/damping", "type": "number", "min": 0, "unit": "s",
   "doc": "Lagged Rayleigh damping k_d of this pair's contacts (as contact.damping)."},

  {"pointer": "/solver", "type": "object", "doc": "Newton's stopping rule and the linear solver."},
  {"pointer": "/solver/tolerance", "type": "number", "default": null, "exclusive_min": 0, "unit": "m/s",
   "default_doc": "1e-2 × bounding-box diagonal / s",
   "doc": "Newton stops when the largest surface-point step divided by h is below this speed (ε_d). A looser one takes fewer iterations but not always less time, and from twice the default the validation inclines (scenes/incline_*.json) fail: their landing step stops before friction has taken the block's speed along the slope (see docs/newton.md, session 62)."},
  {"pointer": "/solver/gap_tolerance", "type": "number", "exclusive_min": 0,
   "doc": "Newton also stops only when its last direction changes no active contact's distance d by more than this fraction of d. Without it a contact pressed deep into the barrier (a landing at speed) can stop at micrometres, far from force balance: the log barrier pushes it out by only a small multiple of its gap per iteration, which the speed rule takes for convergence (see docs/newton.md)."},
  {"pointer": "/solver/max_iterations", "type": "integer", "min": 1,
   "doc": "Newton iteration cap per solve: a time step solves once, and again per friction re-lag (contact.friction_iterations) or kinematic pull round."},
  {"pointer": "/solver/barrier_hessian", "type": "string",
   "options": ["projected", "gauss_newton"],
   "doc": "Newton's Hessian of each contact's barrier: projected (the exact Hessian with its negative eigenvalues clamped to zero, a 5×5 eigen-decomposition per contact, in the span of its distance's gradient and curvature; mollified edge pairs a 9×9 one) or gauss_newton (κ B″(d) ∇d ∇dᵀ, positive semi-definite by construction, leaving out the distance's own curvature; nearly parallel edge pairs keep the projected form). gauss_newton changes Newton's path, not the solution it seeks; over 10 s it takes 4 % fewer iterations on the medium pile at h = 1/1000, between 1 % fewer and 3.1 % more on the seed's other piles at 1/1000 and on all three at 1/240, and without the eigen-decomposition a step at h = 1/1000 costs about a quarter less on medium and full (session 75), but at h = 1/100 up to 12 % more iterations, and on the full pile there it stops steps at the iteration cap, so it is an experiment to check against projected runs, not a safe default (see docs/newton.md)."},
  {"pointer": "/solver/release_hessian", "type": "number", "exclusive_min": 0, "max": 1,
   "doc": "When Newton's direction takes an active contact 35–65 % of the rest of its way out of d̂ (Newton on the barrier's cubic tail takes an unloaded contact half-way out per iteration), the direction is solved again with this fraction of that contact's barrier Hessian (where the first direction already meets solver.tolerance, the second is dropped if the first's full step ends at a lower energy: a loaded contact released overshoots); 1 turns it off. It changes Newton's path, not the minimum a step converges to: 0.6 took 9–22 % of the seed's piles' iterations off at h = 1/1000 with the accuracy studies unchanged; 0.5 makes loaded contacts overshoot (see docs/newton.md)."},
  {"pointer": "/solver/geodesic_line_search", "type": "boolean",
   "doc": "Newton's line-search trials turn affine bodies along the rotation group: with the direction's ΔA A⁻¹ = W + S (skew, symmetric), a body's trial at α is exp(α W) (I + α S) A, cut to the CCD bound of its straight chord from the iterate, wherever the straight line A + α ΔA would stretch it (by about θ² for a turn θ) into an orthogonality energy κ ν ‖W Wᵀ‖² at least the step's promised decrease |gᵀp|; after a geodesic trial that does not lower the energy the search goes on along the straight line; false: always the straight line. It changes Newton's path, not the minimum a step converges to: on the seed's piles 22–34 % fewer iterations at h = 1/100, 7–9 % at 1/240, the same at 1/1000 (see docs/newton.md). Joints' eliminated equalities, linear in q, keep the straight line."},
  {"pointer": "/solver/island_line_search", "type": "boolean",
   "doc": "Bodies that no contact candidate, friction stencil, damped contact or soft element joins on a Newton move form separate islands, and each island gets its own CCD bound and line-search step, so that an impact in one island no longer shortens every other island's step; false: one CCD bound for every body. The energy is a sum over the islands, so each island's part of the direction is a descent direction of its own: it changes Newton's path, not the minimum a step converges to. On the seed's piles 6–19 % fewer iterations at h = 1/100 and 9–14 % on medium and full at 1/240, the same at 1/1000 (see docs/newton.md). A joint joins every body into one island."},
  {"pointer": "/solver/entering_springs", "type": "boolean",
   "doc": "A Newton direction whose first trial CCD cuts is solved again with a one-sided spring on the gap of each pair farther than d̂ that CCD stopped (the barrier is zero there, so Newton's model does not know the pair it is about to hit): the spring lets the pair close to 0.8 d̂ and resists beyond, with stiffness 1e3 m / h² (m the mass it stops); the new direction is kept when it is a descent direction, then bounded by CCD as any other. It changes Newton's path, not the minimum a step converges to: on the seed's piles 9–25 % fewer iterations on medium and full at h = 1/100 and 1/240 (2–6 % on light), within 2 % at 1/1000 and on the hybrid scenes, at 13 % fewer instructions in full's landing and 2 % in medium's (see docs/newton.md, session 44). false: the direction as solved."},
  {"pointer": "/solver/linear", "type": "string",
   "doc": "Linear solver backend: block_cholesky (Cholesky over the dense DOF blocks), block_cg (conjugate gradients with IC(0) over the dense DOF blocks), cholmod (CHOLMOD Cholesky, supernodal or simplicial), petsc (CG + ICC(0)), petsc:KSP[:PC] with KSP in cg, minres, gmres and PC in none, jacobi, pbjacobi, vpbjacobi, icc, gamg, hypre (e.g. petsc:cg:gamg), or auto: a direct factorisation while it is predicted to cost at most 20 Mflop with block_cholesky (every body affine) or 2 Mflop with cholmod (soft bodies), conjugate gradients with IC(0) above: block_cg (every body affine) or PETSc CG + ICC(0) (see docs/linear_solvers.md). PETSc options on the command line (-ksp_type, -pc_type, ...) apply on top."},
  {"pointer": "/solver/krylov_rtol_max", "type": "number", "exclusive_min": 0, "exclusive_max": 1,
   "doc": "Inexact Newton: each Krylov solve stops at the relative residual η given by Eisenstat–Walker's forcing terms, capped by this η_max (see docs/linear_solvers.md); CHOLMOD ignores it."},
  {"pointer": "/solver/rigidity_bound", "type": "number", "exclusive_min": 0,
   "doc": "Largest rigidity error ‖AᵀA − I‖_F an affine body may reach: past it the run stops with an error naming the body (exit code 3), keeping the frames written so far (see docs/robustness.md)."},
  {"pointer": "/solver/sleep_time", "type": "number", "min": 0, "unit": "s",
   "doc": "Affine bodies at rest sleep, as in rigid-body engines (Bullet's deactivation), body by body: a dynamic affine body sleeps once it has touched something and moved no surface point faster than solver.sleep_speed for this long, and so has every dynamic body it touches (or that one sleeps). A sleeping body is held where it is with zero velocity, and its contacts with other sleeping or fixed bodies are left out; a step in which every dynamic body sleeps does no Newton iteration. A body moving faster than sleep_speed wakes every sleeping body its swept box (grown by d̂) meets: predicted at a step's start, before Newton; found at the step's end, the step is solved again with that body awake, so no kept step holds a body that a moving one came within d̂ of. It trades accuracy for time: a sleeping body no longer creeps (friction's slip below ε_v, a pile settling slower than sleep_speed) nor gives way to a body slower than sleep_speed. Bodies touching a soft body never sleep; bodies joined by joints sleep and wake together, and a joint counts as touching. 0 (the default): nothing sleeps (see docs/sleeping.md)."},
  {"pointer": "/solver/sleep_speed", "type": "number", "default": null, "exclusive_min": 0, "unit": "m/s",
   "default_doc": "solver.tolerance (ε_d)",
   "doc": "The speed below which a body counts as at rest for solver.sleep_time: the fastest of its surface points. The default, Newton's own tolerance, is the speed to which a step resolves motion anyway."},

  {"pointer": "/output", "type": "object", "doc": "What is written and how often."},
  {"pointer": "/output/frame_dt", "type": "number", "default": null, "exclusive_min": 0, "unit": "s",
   "default_doc": "max(dt, 1/60 s)",
   "doc": "Time between written frames."},

  {"pointer": "/bodies", "type": "list", "required": true, "min_length": 1,
   "doc": "The bodies of the scene."},
  {"pointer": "/bodies/*", "type": "object", "doc": "One body."},
  {"pointer": "/bodies/*/name", "type": "string", "required": true,
   "doc": "Unique, non-empty name; the ParaView block name."},
  {"pointer": "/bodies/*/kind", "type": "string",
   "options": ["dynamic", "fixed", "kinematic"],
   "doc": "dynamic: moves under forces, as an affine or soft body (see model); fixed: static obstacle; kinematic: rigid, follows its path, then the prescribed velocity and angular_velocity, exactly; a run that cannot keep it on its path without intersection stops with an error (see docs/robustness.md)."},
  {"pointer": "/bodies/*/model", "type": "string",
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
  {"pointer": "/bodies/*/mesh/size", "type": "vector3", "exclusive_min": 0, "max": 1e6,
   "unit": "m", "when": {"primitive": ["box", "plane"]},
   "doc": "box: edge lengths along x, y, z; plane: size along x, thickness along y, size along z."},
  {"pointer": "/bodies/*/mesh/radius", "type": "number", "exclusive_min": 0, "max": 1e6,
   "unit": "m", "when": {"primitive": ["sphere", "cylinder", "torus"]},
   "doc": "Sphere and cylinder radius; torus major (centre-line) radius."},
  {"pointer": "/bodies/*/mesh/minor_radius", "type": "number", "exclusive_min": 0, "max": 1e6,
   "unit": "m", "when": {"primitive": ["torus"]},
   "doc": "Torus tube radius, < radius."},
  {"pointer": "/bodies/*/mesh/height", "type": "number", "exclusive_min": 0, "max": 1e6,
   "unit": "m", "when": {"primitive": ["cylinder"]},
   "doc": "Cylinder height along y."},
  {"pointer": "/bodies/*/mesh/resolution", "type": "integer", "min": 3,
   "when": {"primitive": ["sphere", "cylinder", "torus"]},
   "doc": "Segments around a circle (sphere: around the equator; torus: around both circles)."},
  {"pointer": "/bodies/*/density", "type": "number", "exclusive_min": 0, "max": 1e5,
   "unit": "kg/m³", "doc": "Mass density (unused by fixed and kinematic bodies); the densest element, osmium, has 22 590 kg/m³."},
  {"pointer": "/bodies/*/material", "type": "object", "when": {"model": ["soft", "auto"]},
   "doc": "Elastic material of a soft body (and of an auto body, for the choice)."},
  {"pointer": "/bodies/*/material/model", "type": "string",
   "options": ["linear", "fixed_corotated", "stable_neo_hookean"],
   "doc": "Constitutive model: linear elasticity (small strain only), fixed corotated (Stomakhin et al. 2012) or stable neo-Hookean (Smith et al. 2018; survives inversion)."},
  {"pointer": "/bodies/*/material/young", "type": "number", "exclusive_min": 0, "max": 1e13, "unit": "Pa",
   "doc": "Young's modulus E (diamond: 1.2e12 Pa)."},
  {"pointer": "/bodies/*/material/poisson", "type": "number", "exclusive_min": -1, "exclusive_max": 0.5,
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
  {"pointer": "/bodies/*/dirichlet/*/min", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m",
   "when": {"select": ["box"]}, "doc": "Lower corner of the box."},
  {"pointer": "/bodies/*/dirichlet/*/max", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m",
   "when": {"select": ["box"]}, "doc": "Upper corner of the box."},
  {"pointer": "/bodies/*/dirichlet/*/point", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m",
   "when": {"select": ["half_space"]}, "doc": "A point on the bounding plane."},
  {"pointer": "/bodies/*/dirichlet/*/normal", "type": "vector3",
   "when": {"select": ["half_space"]}, "doc": "Direction into the selected side (need not be unit length)."},
  {"pointer": "/bodies/*/dirichlet/*/node_set", "type": "string",
   "when": {"select": ["node_set"]}, "doc": "Name of the node set."},
  {"pointer": "/bodies/*/dirichlet/*/velocity", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m/s",
   "doc": "Prescribed velocity of the selected nodes: zero holds them fixed, otherwise they move at this velocity, exactly, like kinematic bodies (see docs/robustness.md)."},
  {"pointer": "/bodies/*/kappa", "type": "number", "exclusive_min": 0,
   "unit": "Pa", "doc": "Orthogonality stiffness κ of the affine body; rigidity error ≈ stress / κ."},
  {"pointer": "/bodies/*/position", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m",
   "doc": "Where the mesh's origin goes."},
  {"pointer": "/bodies/*/rotation_deg", "type": "vector3", "unit": "°",
   "doc": "XYZ Euler angles, R = Rz·Ry·Rx (x applied first)."},
  {"pointer": "/bodies/*/scale", "type": "vector3", "exclusive_min": 0, "max": 1e6,
   "doc": "Per-axis scale, applied before the rotation."},
  {"pointer": "/bodies/*/velocity", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m/s",
   "doc": "Initial (kinematic: prescribed) linear velocity of the centre of mass."},
  {"pointer": "/bodies/*/angular_velocity", "type": "vector3", "min": -1e5, "max": 1e5,
   "unit": "rad/s", "doc": "Initial (kinematic: prescribed) angular velocity, world frame."},
  {"pointer": "/bodies/*/path", "type": "list", "default": [], "when": {"kind": ["kinematic"]},
   "doc": "Legs of constant velocity a kinematic body follows first, in order; after the last it moves with velocity and angular_velocity (e.g. press, then release)."},
  {"pointer": "/bodies/*/path/*", "type": "object", "doc": "One leg of a kinematic path."},
  {"pointer": "/bodies/*/path/*/duration", "type": "number", "required": true, "exclusive_min": 0, "unit": "s",
   "doc": "How long the leg lasts."},
  {"pointer": "/bodies/*/path/*/velocity", "type": "vector3", "min": -1e6, "max": 1e6, "unit": "m/s",
   "doc": "Linear velocity of the centre of mass during the leg."},
  {"pointer": "/bodies/*/path/*/angular_velocity", "type": "vector3", "min": -1e5, "max": 1e5, "unit": "rad/s",
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
  {"pointer": "/joints/*/body_b", "type": "string",
   "doc": "Name of the other body, or world. A soft body_b takes ball joints only, at its node nearest to anchor (and every node within nodes_within of it)."},
  {"pointer": "/joints/*/anchor", "type": "vector3", "required": true, "min": -1e6, "max": 1e6, "unit": "m",
   "doc": "The joint's point on body_a (and, for ball, cone_twist, hinge and prismatic joints, on body_b)."},
  {"pointer": "/joints/*/anchor_b", "type": "vector3", "default": null, "min": -1e6, "max": 1e6, "unit": "m",
   "default_doc": "required", "when": {"kind": ["distance", "bounded_distance"]},
   "doc": "The point on body_b whose distance to anchor is kept or bounded."},
  {"pointer": "/joints/*/axis", "type": "vector3",
   "when": {"kind": ["hinge", "prismatic", "cone_twist"]},
   "doc": "Hinge axis through anchor, sliding direction, or the cone-twist axis carried by both bodies (need not be unit length)."},
  {"pointer": "/joints/*/stiffness", "type": "number", "exclusive_min": 0, "unit": "N/m",
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
  {"pointer": "/joints/*/limit_activation", "type": "number", "exclusive_min": 0, "unit": "rad or m",
   "when": {"kind": ["hinge", "prismatic", "bounded_distance", "cone_twist"]},
   "doc": "Activation gap ĝ of the limits' barrier: it pushes only closer than this to a limit."},
  {"pointer": "/joints/*/damping", "type": "number", "min": 0, "unit": "N·m·s/rad or N·s/m",
   "doc": "Lagged viscous damping c of the joint's free coordinate (hinge angle, slide, distance; ball and cone_twist: the two bodies' relative angular velocity ω, not with a soft body_b): dissipation ½ c ṡ² (or ½ c |ω|²) with the map from velocities frozen at the step's start."},
  {"pointer": "/joints/*/nodes_within", "type": "number", "default": null, "exclusive_min": 0, "unit": "m",
   "default_doc": "nearest node only", "when": {"kind": ["ball"]},
   "doc": "Ball joint to a soft body_b: pins every node of body_b within this distance of anchor to the point of body_a it starts at (3 exact rows per node), gluing body_a onto body_b."}
])JSON";

Json vector_json(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

// A schema pointer and the default a default-constructed description struct gives its key.
struct StructDefault {
  const char* pointer;
  Json value;
};

// Every default of kSchemaText that a description struct holds, read from the structs
// themselves: pointer → value. scene_schema() inserts each as the entry's `default`.
std::vector<StructDefault> struct_defaults() {
  const SceneDescription scene{};
  const TimeDescription time{};
  const ContactDescription contact{};
  const ContactPairDescription pair{};
  const SolverDescription solver{};
  const BodyDescription body{};
  const PrimitiveShape primitive{};
  const SoftMaterial material{};
  const DirichletDescription dirichlet{};
  const PathSegment leg{};
  const JointDescription joint{};
  return {
      {"/time/dt", time.dt},
      {"/time/duration", time.duration},
      {"/time/integrator", scene_fields::enum_name(time.integrator)},
      {"/gravity", vector_json(scene.gravity)},
      {"/contact/mu", contact.mu},
      {"/contact/damping", contact.damping},
      {"/contact/balance_kappa", contact.balance_kappa},
      {"/contact/friction_iterations", contact.friction_iterations},
      {"/contact/check_start_gaps", contact.check_start_gaps},
      {"/contact/pairs/*/damping", pair.damping},
      {"/solver/gap_tolerance", solver.gap_tolerance},
      {"/solver/max_iterations", solver.max_iterations},
      {"/solver/barrier_hessian", scene_fields::enum_name(solver.barrier_hessian)},
      {"/solver/release_hessian", solver.release_hessian},
      {"/solver/geodesic_line_search", solver.geodesic_line_search},
      {"/solver/island_line_search", solver.island_line_search},
      {"/solver/entering_springs", solver.entering_springs},
      {"/solver/linear", solver.linear},
      {"/solver/krylov_rtol_max", solver.krylov_rtol_max},
      {"/solver/rigidity_bound", solver.rigidity_bound},
      {"/solver/sleep_time", solver.sleep_time},
      {"/bodies/*/mesh/size", vector_json(primitive.extents)},
      {"/bodies/*/mesh/radius", primitive.radius},
      {"/bodies/*/mesh/minor_radius", primitive.minor_radius},
      {"/bodies/*/mesh/height", primitive.height},
      {"/bodies/*/mesh/resolution", primitive.resolution},
      {"/bodies/*/kind", scene_fields::enum_name(body.kind)},
      {"/bodies/*/model", scene_fields::enum_name(body.model)},
      {"/bodies/*/density", body.density},
      {"/bodies/*/material/model", material.model},
      {"/bodies/*/material/young", material.young},
      {"/bodies/*/material/poisson", material.poisson},
      {"/bodies/*/dirichlet/*/min", vector_json(dirichlet.min)},
      {"/bodies/*/dirichlet/*/max", vector_json(dirichlet.max)},
      {"/bodies/*/dirichlet/*/point", vector_json(dirichlet.point)},
      {"/bodies/*/dirichlet/*/normal", vector_json(dirichlet.normal)},
      {"/bodies/*/dirichlet/*/node_set", dirichlet.node_set},
      {"/bodies/*/dirichlet/*/velocity", vector_json(dirichlet.velocity)},
      {"/bodies/*/kappa", body.kappa},
      {"/bodies/*/position", vector_json(body.position)},
      {"/bodies/*/rotation_deg", vector_json(body.rotation_deg)},
      {"/bodies/*/scale", vector_json(body.scale)},
      {"/bodies/*/velocity", vector_json(body.velocity)},
      {"/bodies/*/angular_velocity", vector_json(body.angular_velocity)},
      {"/bodies/*/path/*/velocity", vector_json(leg.velocity)},
      {"/bodies/*/path/*/angular_velocity", vector_json(leg.angular_velocity)},
      {"/joints/*/body_b", joint.body_b},
      {"/joints/*/axis", vector_json(joint.axis)},
      {"/joints/*/stiffness", joint.stiffness},
      {"/joints/*/limit_activation", joint.limit_activation},
      {"/joints/*/damping", joint.damping},
  };
}

// The parsed text with struct_defaults() inserted, each `default` right after `type` as the
// text writes the others. A pointer that names no entry, or whose entry already has a
// default in the text, is a programming error.
Json with_struct_defaults(Json schema) {
  for (const StructDefault& d : struct_defaults()) {
    Json* target = nullptr;
    for (Json& entry : schema) {
      if (entry.at("pointer") != d.pointer) continue;
      if (target != nullptr)
        throw std::logic_error(std::string("scene schema: two entries for struct default ") + d.pointer);
      target = &entry;
    }
    if (target == nullptr) throw std::logic_error(std::string("scene schema: no entry for struct default ") + d.pointer);
    if (target->contains("default"))
      throw std::logic_error(std::string("scene schema: ") + d.pointer +
                             " has a default in the text and in its struct; keep only the struct's");
    Json entry = Json::object();
    for (const auto& [key, value] : target->items()) {
      entry[key] = value;
      if (key == "type") entry["default"] = d.value;
    }
    *target = std::move(entry);
  }
  return schema;
}

/// The schema's entries by pointer, and the children of every object entry by its pointer.
struct SchemaIndex {
  std::unordered_map<std::string, std::vector<const Json*>> entries;
  std::unordered_map<std::string, std::vector<SchemaChild>> children;
};

const SchemaIndex& schema_index() {
  static const SchemaIndex index = [] {
    SchemaIndex built;
    for (const Json& entry : scene_schema()) {
      const std::string pointer = entry.at("pointer");
      built.entries[pointer].push_back(&entry);
      const std::size_t slash = pointer.rfind('/');
      const std::string key = pointer.substr(slash + 1);
      if (key.empty()) continue;
      std::vector<SchemaChild>& siblings = built.children[slash == 0 ? "/" : pointer.substr(0, slash)];
      if (std::none_of(siblings.begin(), siblings.end(), [&](const SchemaChild& c) { return c.first == key; }))
        siblings.emplace_back(key, &entry);
    }
    return built;
  }();
  return index;
}

}  // namespace

const nlohmann::ordered_json& scene_schema() {
  static const Json schema = with_struct_defaults(Json::parse(kSchemaText));
  return schema;
}

const std::vector<const nlohmann::ordered_json*>& scene_schema_entries(const std::string& pointer) {
  static const std::vector<const Json*> none;
  const auto found = schema_index().entries.find(pointer);
  return found == schema_index().entries.end() ? none : found->second;
}

const std::vector<SchemaChild>& scene_schema_children(const std::string& pointer) {
  static const std::vector<SchemaChild> none;
  const auto found = schema_index().children.find(pointer);
  return found == schema_index().children.end() ? none : found->second;
}

std::string schema_list_text(const nlohmann::ordered_json& list, const std::string& separator) {
  std::string out;
  for (const auto& item : list) {
    if (!out.empty()) out += separator;
    out += item.is_string() ? item.get<std::string>() : item.dump();
  }
  return out;
}

}  // namespace stiffsoft
