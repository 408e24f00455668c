#pragma once
/// @file The Python module's parts (docs/python.md). Every translation unit of the module
/// includes this header first: the scene's lists are opaque, so that `scene.bodies.append(b)`
/// changes the scene itself and not a converted copy.

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <pybind11/stl_bind.h>

#include <stiffsoft/stiffsoft.hpp>

PYBIND11_MAKE_OPAQUE(std::vector<stiffsoft::BodyDescription>)
PYBIND11_MAKE_OPAQUE(std::vector<stiffsoft::JointDescription>)
PYBIND11_MAKE_OPAQUE(std::vector<stiffsoft::DirichletDescription>)
PYBIND11_MAKE_OPAQUE(std::vector<stiffsoft::PathSegment>)
PYBIND11_MAKE_OPAQUE(std::vector<stiffsoft::ContactPairDescription>)

namespace stiffsoft::python {

namespace py = pybind11;

/// Exceptions (SceneError, PhysicsError, StudyError) and their translation.
void bind_errors(py::module_& m);
/// Scenes: the description structs, their enums, loading, dicts and mesh arrays.
void bind_scene(py::module_& m);
/// Registers the Recorder type (its methods come with bind_output()), so that Simulation's
/// signatures can name it.
void declare_recorder(py::module_& m);
/// Simulation: stepping, statistics, state, reading and setting positions.
void bind_simulation(py::module_& m);
/// Output and studies: Recorder, run(), run_study(), threads.
void bind_output(py::module_& m);

}  // namespace stiffsoft::python
