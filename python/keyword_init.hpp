#pragma once
/// @file Keyword constructors for the bound scene structs: `Body(name='box', density=800)`
/// starts from the struct's defaults (scene.hpp, the one place they are written) and sets each
/// keyword as the attribute of that name.

#include <string>

#include <pybind11/pybind11.h>

namespace stiffsoft::python {

/// Adds `__init__(**kwargs)` to `cls`: an unknown keyword is a TypeError naming it, a value of
/// the wrong type a TypeError naming `name.keyword`.
template <class T, class Class>
void keyword_init(Class& cls, const char* name) {
  namespace py = pybind11;
  cls.def(py::init([name](const py::kwargs& keywords) {
            py::object object = py::cast(T{});
            for (const auto& [key, value] : keywords) {
              const std::string k = py::str(key);
              if (!py::hasattr(object, key))
                throw py::type_error(std::string(name) + "() got an unexpected keyword argument '" + k + "'");
              try {
                py::setattr(object, key, value);
              } catch (py::error_already_set& e) {
                const std::string message = std::string(name) + "." + k + ": cannot take " + std::string(py::repr(value)) + " (" + e.what() + ")";
                if (e.matches(PyExc_ValueError)) throw py::value_error(message);
                if (e.matches(PyExc_TypeError)) throw py::type_error(message);
                throw;
              }
            }
            return object.cast<T>();
          }),
          (std::string(name) + "(**keywords): the defaults, with each keyword set as the attribute of that name.").c_str());
}

}  // namespace stiffsoft::python
