/// @file The Python module `stiffsoft`: its docstring, its exceptions, and its parts.

#include "bindings.hpp"

#include <stiffsoft/study/study_spec.hpp>

namespace stiffsoft::python {

void bind_errors(py::module_& m) {
  static py::exception<SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  scene_error.doc() =
      "A scene that cannot be simulated: bad JSON, a value out of range, overlapping bodies.\n\n"
      "str(e) is '<file>: <json path>: <what was expected>'; the attributes `file`, `json_path`\n"
      "and `expected` give the three parts. A scene built in Python is named '<name> (built in\n"
      "code)' unless a label is given. A subclass of ValueError.";
  static py::exception<PhysicsError> physics_error(m, "PhysicsError", PyExc_RuntimeError);
  physics_error.doc() =
      "A step that cannot honour the physics (a kinematic body whose path is blocked, an affine\n"
      "body deformed past solver.rigidity_bound). The step is not taken: the state stays at the\n"
      "last good step. A subclass of RuntimeError.";
  static py::exception<study::StudyError> study_error(m, "StudyError", PyExc_ValueError);
  study_error.doc() = "A study file that cannot be run (docs/accuracy.md). A subclass of ValueError.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      py::object error = py::handle(scene_error.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("json_path") = e.json_path();
      error.attr("expected") = e.expected();
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    } catch (const PhysicsError& e) {
      PyErr_SetString(physics_error.ptr(), e.what());
    } catch (const study::StudyError& e) {
      PyErr_SetString(study_error.ptr(), e.what());
    }
  });
}

}  // namespace stiffsoft::python

PYBIND11_MODULE(stiffsoft, m) {
  m.doc() =
      "stiffsoft: stiff (affine) and soft (tetrahedral FEM) solids in intersection-free contact.\n\n"
      "Every quantity is SI: m, s, kg, N, Pa; angles in rad unless a name says _deg.\n\n"
      "    import stiffsoft\n"
      "    sim = stiffsoft.Simulation('scenes/mixed_pile.json')   # or a Scene, or a dict\n"
      "    for stats in sim.steps(until=0.5):\n"
      "        print(stats.time, stats.newton.iterations)\n"
      "    x = sim.surface()                                     # (|V|, 3) array, m\n\n"
      "Scenes: Scene, Body, Joint, Shape (docs/scenes.md lists every key); stepping and state:\n"
      "Simulation, StepStats, State; output for ParaView: Recorder, run(); studies: run_study().\n"
      "docs/python.md has the whole guide.";
  m.attr("__version__") = STIFFSOFT_VERSION;
  stiffsoft::python::bind_errors(m);
  stiffsoft::python::bind_scene(m);
  stiffsoft::python::declare_recorder(m);
  stiffsoft::python::bind_simulation(m);
  stiffsoft::python::bind_output(m);
}
