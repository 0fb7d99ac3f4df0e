#pragma once
// The core's options structs as Python classes: one property per field (snake_case), constructed
// from keyword arguments with the library's defaults, enums as strings, nested structs settable
// from dicts. A field added to a struct is one .def_readwrite line in options.cpp.
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"

namespace geoshift::python {

// Sets every keyword on the options object `target` (a bound struct): a dict for a field that is
// itself a struct sets that struct's fields. TypeError naming the unknown keyword and the known ones.
void applyOptions(py::handle target, const py::dict& values);

// Registers the options classes on the module.
void bindOptions(py::module_& m);

// T's options from a Python value: None (defaults), a T, or a dict of its fields.
template <class T>
T optionsFrom(const py::handle& value) {
  if (value.is_none()) return T{};
  if (py::isinstance<py::dict>(value)) {
    T t;
    applyOptions(py::cast(&t, py::return_value_policy::reference), py::reinterpret_borrow<py::dict>(value));
    return t;
  }
  return value.cast<T>();
}

// An enum field as a string property (the choices are listed in errors).
template <class T, class E>
void enumField(py::class_<T>& c, const char* name, E T::*field, std::vector<std::pair<std::string, E>> choices) {
  c.def_property(
      name,
      [field, choices](const T& t) {
        for (const auto& [text, value] : choices)
          if (t.*field == value) return text;
        return std::string("?");
      },
      [field, choices, name = std::string(name)](T& t, const std::string& text) {
        std::string known;
        for (const auto& [word, value] : choices) {
          if (word == text) {
            t.*field = value;
            return;
          }
          known += (known.empty() ? "" : ", ") + word;
        }
        throw InputError(name + " must be one of " + known + " (got '" + text + "')");
      });
}

// Enum <-> string for functions that take the choice as an argument.
template <class E>
E choiceOf(const std::string& what, const std::string& text, const std::vector<std::pair<std::string, E>>& choices) {
  std::string known;
  for (const auto& [word, value] : choices) {
    if (word == text) return value;
    known += (known.empty() ? "" : ", ") + word;
  }
  throw InputError(what + " must be one of " + known + " (got '" + text + "')");
}

}  // namespace geoshift::python
