/// @file Python: a Simulation, its steps (one, n, to a time; a callback or an iterator), the
/// statistics of a step, its state, and reading and setting positions and velocities.

#include "py_simulation.hpp"

#include <cmath>

#include <stiffsoft/libabd/affine_body.hpp>
#include <stiffsoft/meshing/intersection.hpp>

namespace stiffsoft::python {

Busy::Busy(PySimulation& s) : m_s(s) {
  if (s.busy.exchange(true)) throw std::runtime_error("the Simulation is stepping in another thread");
}

StepStats take_step(PySimulation& s, PyRecorder* recorder, bool last) {
  StepStats stats;
  {
    Busy busy(s);
    py::gil_scoped_release release;
    stats = s.simulation.step();
    if (recorder && recorder->recorder) recorder->recorder->record(stats, last);
  }
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C: KeyboardInterrupt, after the step
  return stats;
}

namespace {

/// The simulation after checking that no step is running in another thread.
const Simulation& idle(PySimulation& s) {
  Busy busy(s);
  return s.simulation;
}

/// Steps to take for `steps` or `until` (s); neither: to the scene's duration, as `stiffsoft run`.
int steps_to_take(PySimulation& s, std::optional<int> steps, std::optional<double> until) {
  if (steps && until) throw py::value_error("give steps or until, not both");
  if (steps) {
    if (*steps < 0) throw py::value_error("steps: must be >= 0 (got " + std::to_string(*steps) + ")");
    return *steps;
  }
  const double end = until ? *until : s.scene.time.duration;
  if (!std::isfinite(end)) throw py::value_error("until: must be finite");
  return std::max(0, int(std::ceil((end - idle(s).time()) / s.scene.time.dt - 1e-9)));
}

/// Steps `n` times, recording and calling back after each; the recorder is finished on every
/// way out. A callback returning False stops early. Returns the steps' statistics.
std::vector<StepStats> run_steps(PySimulation& s, int n, const py::object& callback, PyRecorder* recorder) {
  std::vector<StepStats> all;
  all.reserve(std::size_t(n));
  try {
    for (int k = 0; k < n; ++k) {
      all.push_back(take_step(s, recorder, k + 1 == n));
      if (!callback.is_none() && callback(all.back()).is(py::bool_(false))) break;
    }
  } catch (...) {
    if (recorder && recorder->recorder) recorder->recorder->finish();
    throw;
  }
  if (recorder && recorder->recorder) recorder->recorder->finish();
  return all;
}

/// `for stats in sim.steps(...)`: one step per item.
struct StepIterator {
  PySimulation& s;
  int remaining;
  PyRecorder* recorder;
};

/// The index of a body given by index or name.
int body_index(const Model& model, const py::object& body) {
  const int n = int(model.bodies.size());
  if (py::isinstance<py::str>(body)) {
    const std::string name = body.cast<std::string>();
    for (int b = 0; b < n; ++b)
      if (model.bodies[std::size_t(b)].name == name) return b;
    throw py::key_error("no body is named \"" + name + "\"");
  }
  const int b = body.cast<int>();
  if (b < 0 || b >= n) throw py::index_error("body " + std::to_string(b) + " out of range (" + std::to_string(n) + " bodies)");
  return b;
}

/// An affine body's index, or a ValueError naming it.
int affine_body(const Model& model, const py::object& body) {
  const int b = body_index(model, body);
  if (model.bodies[std::size_t(b)].representation != Representation::Affine)
    throw py::value_error("body \"" + model.bodies[std::size_t(b)].name + "\" is soft: use its nodes (node_positions(body))");
  return b;
}

/// Rows [begin, end) of `x`, or all of it when `body` is None (`rows` picks the body's range).
Eigen::MatrixX3d rows_of(const Eigen::MatrixX3d& x, const Model& model, const py::object& body,
                         std::pair<int, int> (*range)(const BodyModel&)) {
  if (body.is_none()) return x;
  const auto [begin, end] = range(model.bodies[std::size_t(body_index(model, body))]);
  return x.middleRows(begin, end - begin);
}

/// A body's node range and its surface-vertex range.
std::pair<int, int> node_range(const BodyModel& b) { return {b.node_begin, b.node_end}; }
std::pair<int, int> vertex_range(const BodyModel& b) { return {b.vertex_begin, b.vertex_end}; }

/// A method `name(body=None)`: `field` (a Simulation accessor giving a row per surface vertex
/// or soft node) for all of them, or one body's rows (`range` picks them).
void def_rows(py::class_<PySimulation>& cls, const char* name, Eigen::MatrixX3d (Simulation::*field)() const,
              std::pair<int, int> (*range)(const BodyModel&), const char* doc) {
  cls.def(name, [field, range](PySimulation& s, const py::object& body) {
        const Simulation& sim = idle(s);
        return rows_of((sim.*field)(), sim.model(), body, range);
      },
      py::arg("body") = py::none(), doc);
}

/// A read-only NumPy view of `data` that keeps `owner` alive.
template <class T>
py::array_t<T> view(const T* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle owner) {
  py::array_t<T> a(std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}
template <class T>
py::array_t<T> view(const std::vector<T>& v, py::handle owner) {
  return view(v.data(), {py::ssize_t(v.size())}, {py::ssize_t(sizeof(T))}, owner);
}
template <class Matrix>
py::array_t<typename Matrix::Scalar> view(const Matrix& x, py::handle owner) {
  using T = typename Matrix::Scalar;
  if constexpr (Matrix::ColsAtCompileTime == 1)
    return view<T>(x.data(), {x.rows()}, {py::ssize_t(sizeof(T))}, owner);
  else  // column-major
    return view<T>(x.data(), {x.rows(), x.cols()}, {py::ssize_t(sizeof(T)), py::ssize_t(sizeof(T) * x.rows())}, owner);
}

/// A list of 3-vectors as an (n, 3) array.
Eigen::MatrixX3d stacked(const std::vector<Eigen::Vector3d>& v) {
  Eigen::MatrixX3d x(Eigen::Index(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) x.row(Eigen::Index(i)) = v[i].transpose();
  return x;
}

/// Continues from `state` with its BDF-2 history restarted (previous step = now), after
/// checking that its surfaces are free of intersection; on a ValueError nothing changes.
void set_state(PySimulation& s, SimulationState state) {
  Busy busy(s);
  const Model& model = s.simulation.model();
  state.q_prev = state.q;
  state.qdot_prev = state.qdot;
  const Eigen::MatrixX3d x = model.surface(state.q);
  if (!x.allFinite()) throw py::value_error("the positions are not finite");
  std::vector<SurfaceMesh> surfaces;
  for (const BodyModel& b : model.bodies) {
    SurfaceMesh mesh{x.middleRows(b.vertex_begin, b.vertex_end - b.vertex_begin),
                     model.mesh.F.middleRows(b.face_begin, b.face_end - b.face_begin).array() - b.vertex_begin};
    surfaces.push_back(std::move(mesh));
  }
  if (const auto hit = find_intersection(surfaces))
    throw py::value_error("the new positions make body \"" + model.bodies[std::size_t(hit->surface_a)].name +
                          "\" intersect body \"" + model.bodies[std::size_t(hit->surface_b)].name + "\"");
  s.simulation.restore(state);
}

/// Writes a soft body's (or every soft body's) nodes into `q` (positions) or `qdot`;
/// a ValueError for a wrong shape or a change of a node without DOFs (fixed).
void set_nodes(const Model& model, Eigen::VectorXd& v, const Eigen::MatrixX3d& current, const Eigen::MatrixX3d& values,
               const py::object& body, const char* what) {
  int begin = 0, end = int(model.nodes.size());
  if (!body.is_none()) std::tie(begin, end) = node_range(model.bodies[std::size_t(body_index(model, body))]);
  if (values.rows() != end - begin)
    throw py::value_error(std::string(what) + ": expected " + std::to_string(end - begin) + " rows (got " + std::to_string(values.rows()) + ")");
  for (int i = begin; i < end; ++i) {
    const int dof = model.nodes.dof[std::size_t(i)];
    const Eigen::Vector3d value = values.row(i - begin).transpose();
    if (dof >= 0)
      v.segment<3>(dof) = value;
    else if (value != current.row(i).transpose())
      throw py::value_error(std::string(what) + ": node " + std::to_string(i) + " is fixed and cannot change");
  }
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<PhaseTimes>(m, "PhaseTimes", "Seconds per phase of one step.")
      .def_readonly("broad_phase", &PhaseTimes::broad_phase, "candidate search and active set (s)")
      .def_readonly("ccd", &PhaseTimes::ccd, "continuous collision detection (s)")
      .def_readonly("assembly", &PhaseTimes::assembly, "gradients and Hessians (s)")
      .def_readonly("solve", &PhaseTimes::solve, "linear solves (s)");

  py::class_<NewtonReport>(m, "NewtonReport", "What Newton did in one step.")
      .def_readonly("converged", &NewtonReport::converged, "the stopping rule was met")
      .def_readonly("iterations", &NewtonReport::iterations, "Newton iterations (linear solves)")
      .def_readonly("line_search_steps", &NewtonReport::line_search_steps, "energy evaluations in line searches")
      .def_readonly("line_search_halvings", &NewtonReport::line_search_halvings, "times the line search halved its step")
      .def_readonly("smallest_ccd_step", &NewtonReport::smallest_ccd_step, "smallest step bound from CCD")
      .def_readonly("ccd_limited_iterations", &NewtonReport::ccd_limited_iterations, "iterations whose CCD bound was < 1")
      .def_readonly("revised_directions", &NewtonReport::revised_directions, "directions solved again after friction revised its Hessian")
      .def_readonly("entering_directions", &NewtonReport::entering_directions, "directions solved again with springs on the pairs CCD found entering d-hat")
      .def_readonly("energy", &NewtonReport::energy, "the step's energy at the result (J)")
      .def_readonly("last_step_speed", &NewtonReport::last_step_speed, "largest surface step / h of the last direction (m/s)")
      .def_readonly("linear_iterations", &NewtonReport::linear_iterations, "Krylov iterations (0 for direct solvers)")
      .def_readonly("linear_fallbacks", &NewtonReport::linear_fallbacks, "linear solves a fallback method solved")
      .def_readonly("linear_failure", &NewtonReport::linear_failure, "the first linear-solve failure, empty if none")
      .def_readonly("failure", &NewtonReport::failure, "why it stopped without converging, empty if it converged");

  py::class_<StepStats>(m, "StepStats",
      "What one step did: a row of stats.csv. as_dict() and row() give the stats.csv columns\n"
      "(StepStats.columns()); the attributes give them structured.")
      .def_readonly("step", &StepStats::step, "1-based step index")
      .def_readonly("time", &StepStats::time, "simulated time at the end of the step (s)")
      .def_readonly("newton", &StepStats::newton, "NewtonReport: iterations, line search, convergence")
      .def_property_readonly("converged", [](const StepStats& s) { return s.newton.converged; }, "Newton converged")
      .def_readonly("contacts", &StepStats::contacts, "active contact stencils at the end of the step")
      .def_readonly("smallest_distance", &StepStats::smallest_distance, "smallest active contact distance (m), inf without contact")
      .def_readonly("kinetic_energy", &StepStats::kinetic_energy, "J")
      .def_readonly("potential_energy", &StepStats::potential_energy, "gravitational (J)")
      .def_readonly("elastic_energy", &StepStats::elastic_energy, "soft bodies' strain energy (J)")
      .def_readonly("linear_momentum", &StepStats::linear_momentum, "of the dynamic bodies (kg m/s)")
      .def_readonly("orthogonality_error", &StepStats::orthogonality_error, "largest |A A^T - I|_F of a dynamic affine body")
      .def_readonly("inverted_tets", &StepStats::inverted_tets, "soft tetrahedra with det F <= 0")
      .def_readonly("friction_relags", &StepStats::friction_relags, "times friction was lagged again within the step")
      .def_readonly("friction_lag_error", &StepStats::friction_lag_error,
                    "largest change of a body's velocity that friction lagged at the result would make (m/s)")
      .def_readonly("sticking", &StepStats::sticking, "friction stencils whose slide over the step is inside the stick zone eps_v h")
      .def_readonly("sliding", &StepStats::sliding, "friction stencils whose slide over the step is outside it")
      .def_readonly("stick_slip_flips", &StepStats::stick_slip_flips,
                    "changes of a friction stencil between sticking and sliding from one Newton iterate to the next")
      .def_readonly("kappa", &StepStats::kappa, "barrier stiffness at the end of the step")
      .def_readonly("joint_error", &StepStats::joint_error, "largest violation of the joints' equalities (m)")
      .def_readonly("joint_force", &StepStats::joint_force, "largest joint force (N)")
      .def_readonly("sleeping_bodies", &StepStats::sleeping_bodies, "bodies asleep at the end of the step")
      .def_readonly("times", &StepStats::times, "PhaseTimes: seconds per phase")
      .def_readonly("seconds", &StepStats::seconds, "wall time of the step (s)")
      .def("as_dict", [](const StepStats& s) {
             py::dict d;
             for (const StepStatsColumn& c : step_stats_columns()) d[c.name] = c.value(s);
             return d;
           },
           "The stats.csv columns of this step, by name (floats).")
      .def("row", &step_stats_row, "The stats.csv row of this step, in columns() order.")
      .def_static("columns", &step_stats_column_names, "The stats.csv column names, in order.")
      .def("__repr__", [](const StepStats& s) {
        return "StepStats(step=" + std::to_string(s.step) + ", time=" + py::repr(py::float_(s.time)).cast<std::string>() +
               ", iterations=" + std::to_string(s.newton.iterations) + ", converged=" + (s.newton.converged ? "True" : "False") +
               ", contacts=" + std::to_string(s.contacts) + ")";
      });

  py::class_<SimulationState>(m, "State",
      "Everything that changes from step to step (time, step, q, q-dot and their previous values,\n"
      "the adaptive kappa, the linear solver's choice): Simulation.restore() of the same scene\n"
      "continues from it exactly.\n"
      "Picklable, for checkpoints.")
      .def_readonly("time", &SimulationState::time, "simulated time (s)")
      .def_readonly("step", &SimulationState::step, "steps taken")
      .def_readonly("q", &SimulationState::q, "DOFs")
      .def_readonly("qdot", &SimulationState::qdot, "DOF velocities")
      .def_readonly("kappa", &SimulationState::kappa, "adaptive barrier stiffness")
      .def(py::pickle(
          [](const SimulationState& s) {
            return py::make_tuple(s.time, s.step, s.q, s.qdot, s.q_prev, s.qdot_prev, s.kappa,
                                  s.kappa_balanced, s.solver.decided_nonzeros, s.solver.krylov,
                                  s.sleeping.rest_time, s.sleeping.asleep);
          },
          [](const py::tuple& t) {
            // 8 fields: a pickle from before the solver's choice was kept (the solver chooses anew);
            // 10: from before sleeping bodies (nothing sleeps on restore).
            if (t.size() != 12 && t.size() != 10 && t.size() != 8)
              throw std::runtime_error("State: a pickle of 12 fields was expected");
            SimulationState s{t[0].cast<double>(), t[1].cast<int>(), t[2].cast<Eigen::VectorXd>(),
                              t[3].cast<Eigen::VectorXd>(), t[4].cast<Eigen::VectorXd>(),
                              t[5].cast<Eigen::VectorXd>(), t[6].cast<double>(), t[7].cast<bool>(), {}, {}};
            if (t.size() >= 10) s.solver = {t[8].cast<long>(), t[9].cast<bool>()};
            if (t.size() == 12) s.sleeping = {t[10].cast<Eigen::VectorXd>(), t[11].cast<Eigen::VectorXd>()};
            return s;
          }));

  py::class_<BodyModel>(m, "BodyInfo", "A body as simulated (read only): Simulation.bodies, in scene order.")
      .def_readonly("name", &BodyModel::name)
      .def_property_readonly("representation",
                             [](const BodyModel& b) { return b.representation == Representation::Affine ? "affine" : "soft"; },
                             "'affine' or 'soft'")
      .def_readonly("motion", &BodyModel::motion, "Motion")
      .def_readonly("dof", &BodyModel::dof, "offset of an affine body's 12 DOFs (p, a1, a2, a3) in q; -1 when fixed or soft")
      .def_readonly("mass", &BodyModel::mass, "kg")
      .def_readonly("volume", &BodyModel::volume, "m^3")
      .def_property_readonly("nodes", [](const BodyModel& b) { return py::slice(b.node_begin, b.node_end, 1); }, "slice: a soft body's rows of node arrays")
      .def_property_readonly("tets", [](const BodyModel& b) { return py::slice(b.tet_begin, b.tet_end, 1); }, "slice: a soft body's rows of tets and von_mises()")
      .def_property_readonly("vertices", [](const BodyModel& b) { return py::slice(b.vertex_begin, b.vertex_end, 1); }, "slice: its rows of surface arrays")
      .def_property_readonly("faces", [](const BodyModel& b) { return py::slice(b.face_begin, b.face_end, 1); }, "slice: its rows of triangles")
      .def("__repr__", [](const BodyModel& b) {
        return "BodyInfo(name='" + b.name + "', " + (b.representation == Representation::Affine ? "affine" : "soft") + ")";
      });

  py::class_<StepIterator>(m, "StepIterator", "Steps one step per item: `for stats in sim.steps(...)`.")
      .def("__iter__", [](StepIterator& it) -> StepIterator& { return it; })
      .def("__len__", [](const StepIterator& it) { return it.remaining; })
      .def("__next__", [](StepIterator& it) {
        if (it.remaining <= 0) throw py::stop_iteration();
        --it.remaining;
        return take_step(it.s, it.recorder, it.remaining == 0);
      });

  py::class_<PySimulation> simulation(m, "Simulation",
      "A scene advanced in time. Simulation(scene) takes a scene file path, a Scene or a dict with\n"
      "the keys of a scene file; it meshes soft bodies, resolves relative defaults and checks\n"
      "everything (SceneError naming the JSON path). Steps run with the GIL released; Ctrl-C\n"
      "raises KeyboardInterrupt after the current step.\n\n"
      "Affine body b: 12 DOFs at bodies[b].dof in q, (p, a1, a2, a3), p the centre of mass (m), ai\n"
      "the rows of A. Soft nodes: 3 DOFs each. Arrays are NumPy, (n, 3) per vertex or node.");
  simulation
      .def(py::init([](const SceneDescription& scene, const std::string& label) {
             return std::make_unique<PySimulation>(prepare_scene(scene, label));
           }),
           py::arg("scene"), py::arg("label") = "", "From a Scene; errors name `label` (default: '<name> (built in code)').")
      .def(py::init([](const py::dict& scene, const std::string& label) {
             const py::object s = py::module_::import("stiffsoft").attr("Scene").attr("from_dict")(scene, "", label);
             return std::make_unique<PySimulation>(prepare_scene(s.cast<SceneDescription>(), label));
           }),
           py::arg("scene"), py::arg("label") = "<dict>", "From a dict with the keys of a scene file.")
      .def(py::init([](const std::filesystem::path& file) { return std::make_unique<PySimulation>(prepare_scene(file)); }),
           py::arg("scene"), "From a scene file.")
      .def("step", [](PySimulation& s) { return take_step(s, nullptr, false); },
           "Takes one step of h and returns its StepStats. A step whose Newton iteration did not\n"
           "converge is still taken (stats.converged is False); PhysicsError when it cannot be taken.")
      .def("run",
           [](PySimulation& s, std::optional<int> steps, std::optional<double> until, const py::object& callback,
              PyRecorder* recorder) { return run_steps(s, steps_to_take(s, steps, until), callback, recorder); },
           py::arg("steps") = py::none(), py::arg("until") = py::none(), py::arg("callback") = py::none(),
           py::arg("recorder") = py::none(),
           "Takes `steps` steps, or steps until the time `until` (s), or (neither) to the scene's\n"
           "duration. After each step, `recorder` records it (the last step always writes a frame)\n"
           "and callback(stats) is called; a callback returning False stops. Returns the list of\n"
           "StepStats. The recorder is finished however the run ends (Ctrl-C, an error).")
      .def("steps",
           [](PySimulation& s, std::optional<int> steps, std::optional<double> until, PyRecorder* recorder) {
             return StepIterator{s, steps_to_take(s, steps, until), recorder};
           },
           py::arg("steps") = py::none(), py::arg("until") = py::none(), py::arg("recorder") = py::none(),
           py::keep_alive<0, 1>(), py::keep_alive<0, 4>(),
           "An iterator that takes one step per item and yields its StepStats: `steps` steps, to the\n"
           "time `until` (s), or to the scene's duration; `recorder` records each step.")
      .def_property_readonly("time", [](PySimulation& s) { return idle(s).time(); }, "simulated time (s)")
      .def_property_readonly("step_count", [](PySimulation& s) { return idle(s).state().step; }, "steps taken")
      .def_property_readonly("h", [](PySimulation& s) { return s.scene.time.dt; }, "the time step (s)")
      .def_property_readonly("scene", [](PySimulation& s) { return s.scene; },
                             "a copy of the Scene with every default resolved (d^, eps_v, tolerance, frame_dt)")
      .def_property_readonly("bodies", [](PySimulation& s) { return idle(s).model().bodies; }, "list of BodyInfo, in scene order")
      .def("body", [](PySimulation& s, const py::object& body) { return body_index(idle(s).model(), body); }, py::arg("body"),
           "The index of a body given by name (or index).")
      .def_property_readonly("q", [](PySimulation& s) { return Eigen::VectorXd(idle(s).q()); },
                             "the DOF vector (a copy: a step may replace the simulation's own)")
      .def_property_readonly("qdot", [](PySimulation& s) { return Eigen::VectorXd(idle(s).qdot()); }, "the DOF velocities (a copy)")
      .def("state", [](PySimulation& s) { return idle(s).state(); }, "The State now, for restore().")
      .def("restore", [](PySimulation& s, const SimulationState& state) {
             Busy busy(s);
             s.simulation.restore(state);
           },
           py::arg("state"), "Continues from a State of a Simulation of the same scene (ValueError if its sizes differ).")
      .def("von_mises", [](PySimulation& s) { return idle(s).von_mises(); },
           "Von Mises stress of every soft tetrahedron (Pa), in the order of `tets`.")
      .def("body_pose", [](PySimulation& s, const py::object& body) {
             const Simulation& sim = idle(s);
             const abd::Vector12d q = sim.model().body_q(affine_body(sim.model(), body), sim.q());
             return py::make_tuple(Eigen::Vector3d(abd::translation(q)), abd::affine_matrix(q));
           },
           py::arg("body"), "An affine body's (p, A): centre of mass (m) and affine matrix; x = A x_bar + p.")
      .def("body_rotation", [](PySimulation& s, const py::object& body) {
             const Simulation& sim = idle(s);
             return abd::closest_rotation(abd::affine_matrix(sim.model().body_q(affine_body(sim.model(), body), sim.q())));
           },
           py::arg("body"), "The rotation closest to an affine body's A.")
      .def("body_velocity", [](PySimulation& s, const py::object& body) {
             const Simulation& sim = idle(s);
             const BodyModel& b = sim.model().bodies[std::size_t(affine_body(sim.model(), body))];
             if (b.dof < 0) return py::make_tuple(Eigen::Vector3d::Zero().eval(), Eigen::Vector3d::Zero().eval());
             const abd::Vector12d q = sim.q().segment<12>(b.dof), qdot = sim.qdot().segment<12>(b.dof);
             return py::make_tuple(Eigen::Vector3d(qdot.head<3>()), abd::angular_velocity(q, qdot));
           },
           py::arg("body"), "An affine body's (v, omega): centre-of-mass velocity (m/s), angular velocity (rad/s, world).")
      .def("set_body_pose",
           [](PySimulation& s, const py::object& body, std::optional<Eigen::Vector3d> p, std::optional<Eigen::Matrix3d> A) {
             SimulationState state = idle(s).state();
             const BodyModel& b = s.simulation.model().bodies[std::size_t(affine_body(s.simulation.model(), body))];
             if (b.dof < 0) throw py::value_error("body \"" + b.name + "\" is fixed: it has no pose to set");
             const abd::Vector12d q = state.q.segment<12>(b.dof);
             state.q.segment<12>(b.dof) = abd::make_q(p.value_or(abd::translation(q)), A.value_or(abd::affine_matrix(q)));
             set_state(s, std::move(state));
           },
           py::arg("body"), py::arg("p") = py::none(), py::arg("A") = py::none(),
           "Moves an affine body: centre of mass p (m) and/or affine matrix A (a rotation for a rigid body).\n"
           "ValueError if it would intersect another body; BDF-2's history restarts from here.")
      .def("set_body_velocity",
           [](PySimulation& s, const py::object& body, const Eigen::Vector3d& v, const Eigen::Vector3d& omega) {
             SimulationState state = idle(s).state();
             const BodyModel& b = s.simulation.model().bodies[std::size_t(affine_body(s.simulation.model(), body))];
             if (b.dof < 0) throw py::value_error("body \"" + b.name + "\" is fixed: it has no velocity to set");
             state.qdot.segment<12>(b.dof) = abd::rigid_velocity(state.q.segment<12>(b.dof), v, omega);
             set_state(s, std::move(state));
           },
           py::arg("body"), py::arg("v") = Eigen::Vector3d::Zero().eval(), py::arg("omega") = Eigen::Vector3d::Zero().eval(),
           "Sets an affine body's rigid velocity: v (m/s) of its centre of mass, omega (rad/s, world).")
      .def("set_node_positions",
           [](PySimulation& s, const Eigen::MatrixX3d& x, const py::object& body) {
             SimulationState state = idle(s).state();
             set_nodes(s.simulation.model(), state.q, s.simulation.node_positions(), x, body, "set_node_positions");
             set_state(s, std::move(state));
           },
           py::arg("x"), py::arg("body") = py::none(),
           "Moves soft nodes: every node (|N|, 3), or a soft body's with `body` (m). Fixed nodes must\n"
           "keep their place. ValueError if the surfaces would intersect; BDF-2's history restarts.")
      .def("set_node_velocities",
           [](PySimulation& s, const Eigen::MatrixX3d& v, const py::object& body) {
             SimulationState state = idle(s).state();
             set_nodes(s.simulation.model(), state.qdot, s.simulation.node_velocities(), v, body, "set_node_velocities");
             set_state(s, std::move(state));
           },
           py::arg("v"), py::arg("body") = py::none(), "Sets soft nodes' velocities (m/s), like set_node_positions().")
      .def("joint_forces", [](PySimulation& s) { return stacked(idle(s).joint_forces()); },
           "Force of each joint on its body a at the end of the last step, (joints, 3) in N.")
      .def("joint_positions", [](PySimulation& s) { return stacked(idle(s).joint_positions()); },
           "Each joint's point on body a, (joints, 3) in m.")
      .def_property_readonly("triangles", [](py::object self) { return view(self.cast<PySimulation&>().simulation.model().mesh.F, self); },
                             "surface triangles, (|F|, 3) indices into surface() rows (a read-only view)")
      .def_property_readonly("vertex_body", [](py::object self) { return view(self.cast<PySimulation&>().simulation.model().mesh.vertex_body, self); },
                             "body index of each surface vertex (a read-only view)")
      .def_property_readonly("tets", [](py::object self) { return view(self.cast<PySimulation&>().simulation.model().nodes.T, self); },
                             "soft tetrahedra, (|T|, 4) indices into node rows (a read-only view)")
      .def_property_readonly("rest_positions", [](py::object self) { return view(self.cast<PySimulation&>().simulation.model().nodes.X, self); },
                             "soft nodes' rest positions, (|N|, 3) in m (a read-only view)")
      .def_property_readonly("node_masses", [](py::object self) { return view(self.cast<PySimulation&>().simulation.model().nodes.mass, self); },
                             "lumped mass of each soft node (kg, a read-only view)")
      .def("__repr__", [](PySimulation& s) {
        return "Simulation(scene='" + s.scene.name + "', " + std::to_string(s.scene.bodies.size()) + " bodies, t=" +
               py::repr(py::float_(idle(s).time())).cast<std::string>() + ")";
      });
  def_rows(simulation, "surface", &Simulation::surface, vertex_range,
           "Surface vertices in world coordinates, (|V|, 3) in m; a body's rows with `body`.");
  def_rows(simulation, "surface_velocity", &Simulation::surface_velocity, vertex_range,
           "Surface vertex velocities, (|V|, 3) in m/s.");
  def_rows(simulation, "contact_forces", &Simulation::contact_forces, vertex_range,
           "Barrier force on each surface vertex at the end of the last step, (|V|, 3) in N.");
  def_rows(simulation, "friction_forces", &Simulation::friction_forces, vertex_range,
           "Friction force on each surface vertex over the last step, (|V|, 3) in N.");
  def_rows(simulation, "node_positions", &Simulation::node_positions, node_range,
           "Soft nodes' positions, (|N|, 3) in m; a soft body's rows with `body`.");
  def_rows(simulation, "node_velocities", &Simulation::node_velocities, node_range,
           "Soft nodes' velocities, (|N|, 3) in m/s (zero for fixed nodes).");
}

}  // namespace stiffsoft::python
