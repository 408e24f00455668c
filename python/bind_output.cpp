/// @file Python: output for ParaView (Recorder, run() as `stiffsoft run` does it), convergence
/// studies (run_study() as `stiffsoft study`) and the number of threads.

#include "py_simulation.hpp"

#include <cstdlib>
#include <memory>

#include <tbb/global_control.h>

#include <stiffsoft/study/study.hpp>

namespace stiffsoft::python {

namespace {

/// The `stiffsoft` program for studies: $STIFFSOFT_PROGRAM, else this build tree's, else the
/// installed one, else `stiffsoft` on PATH.
std::filesystem::path stiffsoft_program() {
  if (const char* p = std::getenv("STIFFSOFT_PROGRAM"); p && *p) return p;
  for (const char* candidate : {STIFFSOFT_PROGRAM_BUILD, STIFFSOFT_PROGRAM_INSTALLED})
    if (std::filesystem::exists(candidate)) return candidate;
  return "stiffsoft";
}

/// The limit set by set_threads(), for the rest of the process.
std::unique_ptr<tbb::global_control>& thread_limit() {
  static std::unique_ptr<tbb::global_control> limit;
  return limit;
}

}  // namespace

void declare_recorder(py::module_& m) {
  py::class_<PyRecorder>(m, "Recorder",
      "Writes a run into a folder exactly as `stiffsoft run` does: NAME.pvd and frames/ for\n"
      "ParaView, stats.csv, bodies.csv, joints' output, scene.resolved.json; every file atomically.\n"
      "Pass it to Simulation.run() or .steps(), or call record() after each step; finish() (or the\n"
      "end of a `with` block) flushes the rest.\n\n"
      "    with stiffsoft.Recorder(sim, 'out/drop') as rec:\n"
      "        sim.run(until=1.0, recorder=rec)");
}

void bind_output(py::module_& m) {
  py::reinterpret_borrow<py::class_<PyRecorder>>(m.attr("Recorder"))
      .def(py::init([](PySimulation& s, const std::filesystem::path& out) {
             Busy busy(s);
             return PyRecorder{std::make_unique<Recorder>(out, s.scene, s.simulation)};
           }),
           py::arg("simulation"), py::arg("out"), py::keep_alive<1, 2>(),
           "Creates `out`, writes scene.resolved.json and the frame of the present state.")
      .def("record", [](PyRecorder& r, const StepStats& stats, bool last) {
             if (!r.recorder) throw std::runtime_error("Recorder: already finished");
             py::gil_scoped_release release;
             r.recorder->record(stats, last);
           },
           py::arg("stats"), py::arg("last") = false,
           "Records the step just taken; writes a frame every output.frame_dt and when `last` is True.")
      .def("finish", [](PyRecorder& r) {
             if (r.recorder) r.recorder->finish();
           },
           "Waits for the writes in flight and flushes the rest; the files are complete when it returns.")
      .def_property_readonly("frame_count", [](const PyRecorder& r) { return r.recorder ? r.recorder->frame_count() : 0; },
                             "frames on disk so far")
      .def_property_readonly("pvd_path", [](const PyRecorder& r) { return r.recorder ? r.recorder->pvd_path() : std::filesystem::path(); },
                             "OUT/NAME.pvd, for ParaView")
      .def("__enter__", [](PyRecorder& r) -> PyRecorder& { return r; })
      .def("__exit__", [](PyRecorder& r, const py::args&) {
        if (r.recorder) r.recorder->finish();
        return false;
      });

  m.def("run",
        [](const py::object& scene, const std::filesystem::path& out, std::optional<int> steps, const py::object& callback) {
          const py::module_ stiffsoft = py::module_::import("stiffsoft");
          const py::object simulation = stiffsoft.attr("Simulation")(scene);
          const py::object recorder = stiffsoft.attr("Recorder")(simulation, out);
          return simulation.attr("run")(steps, py::none(), callback, recorder);
        },
        py::arg("scene"), py::arg("out"), py::arg("steps") = py::none(), py::arg("callback") = py::none(),
        "What `stiffsoft run SCENE -o OUT [--steps N]` does: runs a scene (a file, a Scene or a dict)\n"
        "to its duration (or `steps` steps) and writes the same files. Returns the StepStats list.");

  m.def("run_study",
        [](const std::filesystem::path& study, const std::filesystem::path& out, int jobs, bool check) {
          study::StudyOptions options{study, out, jobs, check, stiffsoft_program()};
          py::gil_scoped_release release;
          return study::run_study(options);
        },
        py::arg("study"), py::arg("out"), py::arg("jobs") = 0, py::arg("check") = true,
        "What `stiffsoft study STUDY -o OUT` does (docs/accuracy.md): runs the sweep's scenes as\n"
        "`stiffsoft run` processes (`jobs` at a time, 0: one per core; runs already in OUT/runs are\n"
        "reused), checks their frames unless `check` is False, and writes OUT/study.csv,\n"
        "OUT/report.md and the plots. Returns 0, or 1 when the plots could not be drawn. The\n"
        "program is $STIFFSOFT_PROGRAM, else the build's or the installed `stiffsoft`.");

  m.def("set_threads",
        [](int threads) {
          if (threads < 0) throw py::value_error("threads: must be >= 0 (got " + std::to_string(threads) + ")");
          thread_limit().reset();
          if (threads > 0)
            thread_limit() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
        },
        py::arg("threads"),
        "Limits the threads every simulation of this process uses (as `stiffsoft run --threads`);\n"
        "0: no limit (all cores). Results do not depend on it.");
}

}  // namespace stiffsoft::python
