/// @file Python: scenes. The description structs of stiffsoft/scene/scene.hpp with their
/// defaults, keyword constructors, enums that also take their scene-file names, dicts and JSON
/// in and out, and mesh files written from NumPy arrays.

#include "bindings.hpp"
#include "keyword_init.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/meshing/tet_mesh_cache.hpp>
#include <stiffsoft/meshing/tet_msh_io.hpp>
// The scene-file names of the enums, kept in one list there (private to the scene library;
// the module is the one other reader, so that `kind="fixed"` means what it means in a file).
#include <stiffsoft/scene/scene_fields.hpp>

namespace stiffsoft::python {

namespace {

/// An enum whose values are named as in scene files (`stiffsoft.Motion.fixed`) and which a
/// Python string converts to (`body.kind = "fixed"`); an unknown name is a ValueError listing
/// the known ones.
template <class E>
void bind_enum(py::module_& m, const char* name, const char* doc) {
  py::enum_<E> e(m, name, doc);
  const auto& names = scene_fields::EnumNames<E>::names;
  for (std::size_t i = 0; i < names.size(); ++i) e.value(names[i], E(i));
  e.def(py::init([name](const std::string& text) {
          const auto& known = scene_fields::EnumNames<E>::names;
          std::string list;
          for (std::size_t i = 0; i < known.size(); ++i) {
            if (text == known[i]) return E(i);
            list += (i ? ", " : "") + std::string(known[i]);
          }
          throw py::value_error(std::string(name) + ": unknown value \"" + text + "\" (expected one of " + list + ")");
        }),
        py::arg("name"), "The value of this scene-file name.");
}

/// The enum value of `value`: an E, or the scene-file name of one (a ValueError listing the
/// names otherwise).
template <class E>
E enum_value(const py::handle& value) {
  const std::string type = py::str(py::type::of<E>().attr("__name__"));
  if (py::isinstance<E>(value)) return value.cast<E>();
  if (!py::isinstance<py::str>(value))
    throw py::type_error(type + ": expected a " + type + " or its name (got " + std::string(py::repr(value)) + ")");
  return py::type::of<E>()(value).template cast<E>();
}

/// A read-write enum member that takes an E or its scene-file name (`body.kind = "fixed"`).
template <class C, class E>
void def_enum(py::class_<C>& cls, const char* name, E C::*member, const char* doc) {
  cls.def_property(name, [member](const C& c) { return c.*member; },
                   [member](C& c, const py::object& value) { c.*member = enum_value<E>(value); }, doc);
}

/// A list type bound by reference (so that `scene.bodies.append(b)` changes the scene), which
/// a Python list or any iterable of the element converts to.
template <class T>
void bind_list(py::module_& m, const char* name) {
  py::bind_vector<std::vector<T>>(m, name);
  py::implicitly_convertible<py::list, std::vector<T>>();
  py::implicitly_convertible<py::tuple, std::vector<T>>();
}

/// `rows`: a (n, columns) array of `kind` ("vertices" or an index list), checked.
template <class Matrix>
Matrix checked_rows(const py::object& rows, int columns, const char* argument) {
  Matrix result;
  try {
    result = rows.cast<Matrix>();
  } catch (const py::cast_error&) {
    throw py::value_error(std::string(argument) + ": expected an array of shape (n, " + std::to_string(columns) + ")");
  }
  if (result.rows() == 0) throw py::value_error(std::string(argument) + ": is empty");
  return result;
}

/// Checks that every index of `indices` is a row of `vertices`.
template <class Indices>
void check_indices(const Indices& indices, Eigen::Index vertices, const char* argument) {
  if (indices.minCoeff() < 0 || indices.maxCoeff() >= vertices)
    throw py::value_error(std::string(argument) + ": indices must lie in [0, " + std::to_string(vertices) +
                          ") (got " + std::to_string(indices.minCoeff()) + " to " + std::to_string(indices.maxCoeff()) + ")");
}

/// Writes a surface (.obj) or tetrahedra (.msh) from arrays; returns the path written.
std::filesystem::path write_mesh(const std::filesystem::path& path, const py::object& vertices,
                                 const py::object& triangles, const py::object& tets) {
  if (triangles.is_none() == tets.is_none())
    throw py::value_error("write_mesh: give either triangles (a surface, .obj) or tets (a volume, .msh)");
  const auto V = checked_rows<Eigen::MatrixX3d>(vertices, 3, "vertices");
  if (!V.allFinite()) throw py::value_error("vertices: must be finite");
  const std::string extension = path.extension().string();
  if (!triangles.is_none()) {
    if (extension != ".obj") throw py::value_error("write_mesh: a surface is written as .obj (got \"" + path.string() + "\")");
    const auto F = checked_rows<Eigen::MatrixX3i>(triangles, 3, "triangles");
    check_indices(F, V.rows(), "triangles");
    write_file_atomically(path, [&](std::ostream& out) {
      char line[96];
      for (Eigen::Index i = 0; i < V.rows(); ++i) {
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", V(i, 0), V(i, 1), V(i, 2));
        out << line;
      }
      for (Eigen::Index f = 0; f < F.rows(); ++f) out << "f " << F(f, 0) + 1 << ' ' << F(f, 1) + 1 << ' ' << F(f, 2) + 1 << '\n';
    });
    return path;
  }
  if (extension != ".msh") throw py::value_error("write_mesh: tetrahedra are written as .msh (got \"" + path.string() + "\")");
  TetMesh mesh{V, checked_rows<Eigen::MatrixX4i>(tets, 4, "tets"), {}};
  check_indices(mesh.T, V.rows(), "tets");
  write_msh(path, mesh);
  return path;
}

/// A mesh file for arrays, named by its content in `folder` (default: `arrays/` in the mesh cache).
std::filesystem::path mesh_file(const py::object& vertices, const py::object& triangles, const py::object& tets,
                                const std::filesystem::path& folder) {
  const std::filesystem::path dir = folder.empty() ? tet_mesh_cache_folder() / "arrays" : folder;
  std::filesystem::create_directories(dir);
  const bool surface = !triangles.is_none();
  // A scratch name of this process, so that processes sharing the folder never read each other's.
  const std::filesystem::path scratch =
      dir / (".scratch." + std::to_string(::getpid()) + (surface ? ".obj" : ".msh"));
  const std::filesystem::path written = write_mesh(scratch, vertices, triangles, tets);
  std::ifstream in(written, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  char name[40];
  std::snprintf(name, sizeof name, "%016llx%s", static_cast<unsigned long long>(fnv1a_64(bytes)), surface ? ".obj" : ".msh");
  const std::filesystem::path target = std::filesystem::absolute(dir / name);
  std::filesystem::rename(written, target);
  return target;
}

/// SceneDescription from a dict with the keys of a scene file (docs/scenes.md).
SceneDescription scene_from_dict(const py::dict& d, const std::filesystem::path& folder, const std::string& label) {
  const std::string text = py::module_::import("json").attr("dumps")(d).cast<std::string>();
  const std::string name = d.contains("name") ? py::str(d["name"]).cast<std::string>() : "scene";
  return load_scene_from_string(text, folder.empty() ? std::filesystem::current_path() : folder, label, name);
}

/// The scene as a dict: the content of `scene.resolved.json`.
py::object scene_to_dict(const SceneDescription& scene) {
  return py::module_::import("json").attr("loads")(resolved_scene_json(scene).dump());
}

}  // namespace

void bind_scene(py::module_& m) {
  bind_enum<Motion>(m, "Motion", "How a body moves: dynamic, fixed or kinematic (a prescribed path).");
  bind_enum<ModelChoice>(m, "Model", "How a dynamic body is discretised: affine (12 DOFs), soft (tetrahedral FEM) or auto.");
  bind_enum<Integrator>(m, "Integrator", "Time integrator: backward_euler (order 1) or bdf2 (order 2).");
  bind_enum<PrimitiveShape::Type>(m, "ShapeType", "A primitive shape: box, sphere, cylinder, torus or plane.");
  bind_enum<JointKind>(m, "JointKind", "A joint: ball, hinge, prismatic, distance, bounded_distance or cone_twist (docs/joints.md).");
  bind_enum<contact::BarrierHessian>(m, "BarrierHessian", "Newton's Hessian of a contact's barrier: projected or gauss_newton.");
  bind_enum<DirichletDescription::Select>(m, "Select", "How Dirichlet nodes are chosen: box, half_space or node_set.");

  py::class_<PrimitiveShape> shape(m, "Shape",
      "A primitive shape centred at the origin, axis of symmetry along y (scene key bodies[].mesh.primitive).\n\n"
      "    Shape(type='sphere', radius=0.1)   or   Shape.sphere(0.1)");
  keyword_init<PrimitiveShape>(shape, "Shape");
  def_enum(shape, "type", &PrimitiveShape::type, "ShapeType (or its name)");
  shape.def_readwrite("extents", &PrimitiveShape::extents, "a box's edge lengths along x, y, z (m); a plane's size x, thickness y, size z (m)")
      .def_readwrite("radius", &PrimitiveShape::radius, "sphere and cylinder radius, torus centre-line radius (m)")
      .def_readwrite("minor_radius", &PrimitiveShape::minor_radius, "torus tube radius (m)")
      .def_readwrite("height", &PrimitiveShape::height, "cylinder height along y (m)")
      .def_readwrite("resolution", &PrimitiveShape::resolution, "segments around a circle, >= 3")
      .def_static("box", [](const Eigen::Vector3d& e) { return PrimitiveShape{PrimitiveShape::Type::Box, e}; },
                  py::arg("extents"), "A box with these edge lengths along x, y, z (m).")
      .def_static("sphere", [](double r, int n) { PrimitiveShape s; s.type = PrimitiveShape::Type::Sphere; s.radius = r; s.resolution = n; return s; },
                  py::arg("radius"), py::arg("resolution") = PrimitiveShape{}.resolution, "A sphere of this radius (m).")
      .def_static("cylinder", [](double r, double h, int n) { PrimitiveShape s; s.type = PrimitiveShape::Type::Cylinder; s.radius = r; s.height = h; s.resolution = n; return s; },
                  py::arg("radius"), py::arg("height"), py::arg("resolution") = PrimitiveShape{}.resolution, "A cylinder along y (m).");

  py::class_<SoftMaterial> material(m, "Material", "Material of a soft body (bodies[].material).");
  keyword_init<SoftMaterial>(material, "Material");
  material.def_readwrite("model", &SoftMaterial::model, "'linear', 'fixed_corotated' or 'stable_neo_hookean'")
      .def_readwrite("young", &SoftMaterial::young, "Young's modulus E (Pa)")
      .def_readwrite("poisson", &SoftMaterial::poisson, "Poisson ratio, in (-1, 0.5)");

  py::class_<PathSegment> segment(m, "PathSegment", "One leg of a kinematic body's path: constant velocities for a duration.");
  keyword_init<PathSegment>(segment, "PathSegment");
  segment.def_readwrite("duration", &PathSegment::duration, "s, > 0")
      .def_readwrite("velocity", &PathSegment::velocity, "linear velocity of the centre of mass (m/s)")
      .def_readwrite("angular_velocity", &PathSegment::angular_velocity, "world frame (rad/s)");

  py::class_<DirichletDescription> dirichlet(m, "Dirichlet", "Prescribed nodes of a soft body (bodies[].dirichlet[]).");
  keyword_init<DirichletDescription>(dirichlet, "Dirichlet");
  def_enum(dirichlet, "select", &DirichletDescription::select, "Select (or its name): box, half_space or node_set");
  dirichlet.def_readwrite("min", &DirichletDescription::min, "box lower corner (m)")
      .def_readwrite("max", &DirichletDescription::max, "box upper corner (m)")
      .def_readwrite("point", &DirichletDescription::point, "half-space plane point (m)")
      .def_readwrite("normal", &DirichletDescription::normal, "half-space direction: (x - point).normal >= 0 is selected")
      .def_readwrite("node_set", &DirichletDescription::node_set, "a named node set of the mesh file")
      .def_readwrite("velocity", &DirichletDescription::velocity, "prescribed velocity (m/s); zero: fixed");

  bind_list<PathSegment>(m, "PathList");
  bind_list<DirichletDescription>(m, "DirichletList");

  py::class_<BodyDescription> body(m, "Body",
      "One body of a scene (bodies[]). Its geometry is a primitive `shape` or a `mesh_file`\n"
      "(.obj, .stl, .msh, .step, .brep, .geo; set_mesh() writes one from arrays).\n\n"
      "    Body(name='box', shape=Shape.box((0.4, 0.2, 0.4)), position=(0, 0.1, 0), density=800)");
  keyword_init<BodyDescription>(body, "Body");
  def_enum(body, "kind", &BodyDescription::kind, "Motion (or its name): dynamic, fixed or kinematic");
  def_enum(body, "model", &BodyDescription::model, "Model (or its name): affine, soft or auto");
  body.def_readwrite("name", &BodyDescription::name, "unique; the ParaView block name")
      .def_property("shape", [](const BodyDescription& b) { return b.mesh.primitive; },
                    [](BodyDescription& b, const std::optional<PrimitiveShape>& s) {
                      b.mesh.primitive = s;
                      if (s) b.mesh.file.clear();
                    },
                    "the primitive Shape, or None when the body is a mesh file")
      .def_property("mesh_file", [](const BodyDescription& b) { return b.mesh.file; },
                    [](BodyDescription& b, const std::filesystem::path& file) {
                      b.mesh.file = file;
                      b.mesh.primitive.reset();
                    },
                    "the mesh file (absolute, or relative to the working directory); empty for a shape")
      .def("set_mesh",
           [](BodyDescription& b, const py::object& vertices, const py::object& triangles, const py::object& tets,
              const std::filesystem::path& folder) {
             b.mesh.file = mesh_file(vertices, triangles, tets, folder);
             b.mesh.primitive.reset();
           },
           py::arg("vertices"), py::arg("triangles") = py::none(), py::arg("tets") = py::none(), py::arg("folder") = "",
           "Makes the body's geometry from arrays: vertices (n, 3) in m and either triangles (m, 3)\n"
           "(a closed outward surface) or tets (m, 4) (a tetrahedral mesh, used as is by a soft body).\n"
           "Writes them with mesh_file(), so that the scene stays a file `stiffsoft run` can run.")
      .def_readwrite("density", &BodyDescription::density, "kg/m^3, > 0")
      .def_readwrite("material", &BodyDescription::material, "Material of a soft or auto body")
      .def_readwrite("mesh_size", &BodyDescription::mesh_size, "target tet edge length (m); None: 1/8 of the body's box diagonal")
      .def_readwrite("dirichlet", &BodyDescription::dirichlet, "DirichletList: prescribed nodes of a soft body (Dirichlet items)")
      .def_readwrite("kappa", &BodyDescription::kappa, "orthogonality stiffness of an affine body (Pa)")
      .def_readwrite("position", &BodyDescription::position, "where the mesh's origin goes (m)")
      .def_readwrite("rotation_deg", &BodyDescription::rotation_deg, "XYZ Euler angles (degrees), R = Rz Ry Rx")
      .def_readwrite("scale", &BodyDescription::scale, "per-axis scale applied before rotation")
      .def_readwrite("velocity", &BodyDescription::velocity, "initial (kinematic: prescribed) velocity of the centre of mass (m/s)")
      .def_readwrite("angular_velocity", &BodyDescription::angular_velocity, "initial (kinematic: prescribed) angular velocity, world (rad/s)")
      .def_readwrite("path", &BodyDescription::path, "PathList: a kinematic body's legs (PathSegment items), followed first")
      .def("__repr__", [](const BodyDescription& b) {
        return "Body(name='" + b.name + "', kind=" + scene_fields::enum_name(b.kind) + ", model=" + scene_fields::enum_name(b.model) + ")";
      });

  py::class_<JointDescription> joint(m, "Joint", "A joint between two bodies, points and axes in the world frame at the initial pose (docs/joints.md).");
  keyword_init<JointDescription>(joint, "Joint");
  def_enum(joint, "kind", &JointDescription::kind, "JointKind (or its name)");
  joint.def_readwrite("name", &JointDescription::name, "unique, for errors and output")
      .def_readwrite("body_a", &JointDescription::body_a, "an affine body's name")
      .def_readwrite("body_b", &JointDescription::body_b, "another body's name, or 'world'")
      .def_readwrite("anchor", &JointDescription::anchor, "the joint point, on body a (m)")
      .def_readwrite("anchor_b", &JointDescription::anchor_b, "the point on body b of distance kinds (m)")
      .def_readwrite("axis", &JointDescription::axis, "hinge, prismatic and cone-twist axis")
      .def_readwrite("stiffness", &JointDescription::stiffness, "penalty stiffness of distance and prismatic joints (N/m)")
      .def_readwrite("lower", &JointDescription::lower, "lower limit (rad for hinges, m otherwise); None: none")
      .def_readwrite("upper", &JointDescription::upper, "upper limit (rad for hinges, m otherwise); None: none")
      .def_readwrite("swing", &JointDescription::swing, "cone-twist: largest bend (rad)")
      .def_readwrite("twist_lower", &JointDescription::twist_lower, "cone-twist: lowest twist (rad, < 0)")
      .def_readwrite("twist_upper", &JointDescription::twist_upper, "cone-twist: highest twist (rad, > 0)")
      .def_readwrite("limit_stiffness", &JointDescription::limit_stiffness, "limit barrier stiffness (J); None: automatic")
      .def_readwrite("limit_activation", &JointDescription::limit_activation, "limit barrier activation gap (rad or m)")
      .def_readwrite("damping", &JointDescription::damping, "viscous damping of the free coordinate (N m s/rad or N s/m)")
      .def_readwrite("nodes_within", &JointDescription::nodes_within, "a ball joint to a soft body pins every node within this distance of the anchor (m); None: the nearest");

  py::class_<TimeDescription> time(m, "TimeSettings", "scene key `time`: step size, duration, integrator.");
  keyword_init<TimeDescription>(time, "TimeSettings");
  time.def_readwrite("dt", &TimeDescription::dt, "time step h (s), > 0")
      .def_readwrite("duration", &TimeDescription::duration, "simulated time (s), > 0");
  def_enum(time, "integrator", &TimeDescription::integrator, "Integrator (or its name): backward_euler or bdf2");

  py::class_<ContactPairDescription> pair(m, "ContactPair", "contact.pairs[]: settings for the contacts between two named bodies.");
  keyword_init<ContactPairDescription>(pair, "ContactPair");
  pair.def_readwrite("body_a", &ContactPairDescription::body_a, "a body's name")
      .def_readwrite("body_b", &ContactPairDescription::body_b, "a body's name (may equal body_a: self-contact)")
      .def_readwrite("damping", &ContactPairDescription::damping, "contact damping of this pair (s), >= 0");
  bind_list<ContactPairDescription>(m, "ContactPairList");

  py::class_<ContactDescription> contact(m, "ContactSettings",
      "scene key `contact`: the IPC barrier and friction. None: relative to the scene's size (docs/units.md).");
  keyword_init<ContactDescription>(contact, "ContactSettings");
  contact.def_readwrite("dhat", &ContactDescription::dhat, "barrier activation distance d^ (m); None: 1e-3 x the scene's diagonal")
      .def_readwrite("mu", &ContactDescription::mu, "Coulomb friction coefficient, >= 0")
      .def_readwrite("eps_v", &ContactDescription::eps_v, "static/kinetic smoothing speed (m/s); None: 1e-3 x diagonal / s")
      .def_readwrite("kappa", &ContactDescription::kappa, "fixed barrier stiffness (Pa m); None: adaptive")
      .def_readwrite("balance_kappa", &ContactDescription::balance_kappa, "adaptive kappa: balance it once, at the first contact")
      .def_readwrite("friction_iterations", &ContactDescription::friction_iterations,
                     "friction lags per step, >= 1: again at the result while the lag error exceeds eps_v / 10; above 1, Newton also resolves sticking contacts to eps_v h / 10")
      .def_readwrite("damping", &ContactDescription::damping, "lagged contact damping (s), >= 0")
      .def_readwrite("check_start_gaps", &ContactDescription::check_start_gaps, "refuse bodies starting closer than d^")
      .def_readwrite("pairs", &ContactDescription::pairs, "ContactPairList: per-pair settings (ContactPair items)");

  py::class_<SolverDescription> solver(m, "SolverSettings", "scene key `solver`: Newton's stopping rule and the linear solver.");
  keyword_init<SolverDescription>(solver, "SolverSettings");
  solver.def_readwrite("tolerance", &SolverDescription::tolerance, "Newton tolerance (m/s); None: 1e-2 x diagonal / s")
      .def_readwrite("gap_tolerance", &SolverDescription::gap_tolerance,
                     "Newton also needs every active contact's gap to change by at most this fraction")
      .def_readwrite("max_iterations", &SolverDescription::max_iterations, "Newton iteration cap per solve")
      .def_readwrite("release_hessian", &SolverDescription::release_hessian,
                     "fraction of its barrier Hessian a contact keeps when a direction takes it 35-65 % of the way out of d-hat")
      .def_readwrite("geodesic_line_search", &SolverDescription::geodesic_line_search,
                     "line-search trials turn affine bodies along the rotation group, exp(alpha W) (I + alpha S) A")
      .def_readwrite("island_line_search", &SolverDescription::island_line_search,
                     "each island of uncoupled bodies gets its own CCD bound and line-search step")
      .def_readwrite("entering_springs", &SolverDescription::entering_springs,
                     "a direction CCD cuts is solved again with one-sided springs on the pairs entering d-hat")
      .def_readwrite("linear", &SolverDescription::linear, "the linear solver ('auto', 'cholmod', 'petsc', 'petsc:KSP[:PC]')")
      .def_readwrite("krylov_rtol_max", &SolverDescription::krylov_rtol_max, "largest relative residual of a Krylov solve")
      .def_readwrite("rigidity_bound", &SolverDescription::rigidity_bound, "largest |A^T A - I|_F of an affine body before the run stops")
      .def_readwrite("sleep_time", &SolverDescription::sleep_time,
                     "seconds at rest after which an affine body, beside bodies at rest, sleeps (s); 0: never")
      .def_readwrite("sleep_speed", &SolverDescription::sleep_speed,
                     "speed below which a body rests (m/s); None: the Newton tolerance");
  def_enum(solver, "barrier_hessian", &SolverDescription::barrier_hessian,
           "BarrierHessian (or its name): projected or gauss_newton");

  py::class_<OutputDescription> output(m, "OutputSettings", "scene key `output`.");
  keyword_init<OutputDescription>(output, "OutputSettings");
  output.def_readwrite("frame_dt", &OutputDescription::frame_dt, "time between written frames (s); None: max(dt, 1/60 s)");

  bind_list<BodyDescription>(m, "BodyList");
  bind_list<JointDescription>(m, "JointList");

  py::class_<SceneDescription> scene(m, "Scene",
      "A whole scene: the tree of a scene file (docs/scenes.md lists every key, default and unit).\n\n"
      "    scene = Scene(name='drop')\n"
      "    scene.time.dt = 0.01\n"
      "    scene.bodies.append(Body(name='ground', kind='fixed', shape=Shape.box((2, 0.1, 2))))\n\n"
      "Scene.load(file), Scene.from_dict(d) and Simulation(scene) check it exactly as a scene\n"
      "file is checked; errors are SceneError naming the JSON path.");
  keyword_init<SceneDescription>(scene, "Scene");
  scene.def_readwrite("name", &SceneDescription::name, "the scene's name (output files are named after it)")
      .def_readwrite("description", &SceneDescription::description, "what the scene shows")
      .def_readwrite("time", &SceneDescription::time, "TimeSettings")
      .def_readwrite("gravity", &SceneDescription::gravity, "m/s^2")
      .def_readwrite("contact", &SceneDescription::contact, "ContactSettings")
      .def_readwrite("solver", &SceneDescription::solver, "SolverSettings")
      .def_readwrite("output", &SceneDescription::output, "OutputSettings")
      .def_readwrite("bodies", &SceneDescription::bodies, "BodyList: the bodies (Body items), in order")
      .def_readwrite("joints", &SceneDescription::joints, "JointList: the joints (Joint items)")
      .def_static("load", [](const std::filesystem::path& file) { return load_scene(file); }, py::arg("file"),
                  "Reads and checks a scene file (SceneError naming the file and JSON path).")
      .def_static("from_dict", &scene_from_dict, py::arg("scene"), py::arg("folder") = "", py::arg("label") = "<dict>",
                  "A scene from a dict with the keys of a scene file, checked as a file is; `folder`\n"
                  "resolves relative mesh paths (default: the working directory); `label` names the\n"
                  "source in errors.")
      .def("to_dict", &scene_to_dict, "The scene as a dict with every default written out (scene.resolved.json).")
      .def("save", [](const SceneDescription& s, const std::filesystem::path& file) {
             write_file_atomically(file, [&](std::ostream& out) { out << resolved_scene_json(s).dump(1) << '\n'; });
           },
           py::arg("file"), "Writes the scene as a scene file that `stiffsoft run` runs.")
      .def("body", [](SceneDescription& s, const std::string& name) -> BodyDescription& {
             for (BodyDescription& b : s.bodies)
               if (b.name == name) return b;
             throw py::key_error("no body is named \"" + name + "\"");
           },
           py::arg("name"), py::return_value_policy::reference_internal, "The body of this name (a reference: changes change the scene).")
      .def("__repr__", [](const SceneDescription& s) {
        return "Scene(name='" + s.name + "', " + std::to_string(s.bodies.size()) + " bodies, " +
               std::to_string(s.joints.size()) + " joints, dt=" + py::repr(py::float_(s.time.dt)).cast<std::string>() + ")";
      });

  m.def("write_mesh", &write_mesh, py::arg("path"), py::arg("vertices"), py::arg("triangles") = py::none(),
        py::arg("tets") = py::none(),
        "Writes vertices (n, 3) in m with triangles (m, 3) as .obj or with tets (m, 4) as .msh\n"
        "(atomically); returns the path. Indices are 0-based.");
  m.def("mesh_file", &mesh_file, py::arg("vertices"), py::arg("triangles") = py::none(), py::arg("tets") = py::none(),
        py::arg("folder") = "",
        "Like write_mesh(), into a file named by its content in `folder` (default: arrays/ in the\n"
        "mesh cache, docs/soft_bodies.md); returns its absolute path.");
}

}  // namespace stiffsoft::python
