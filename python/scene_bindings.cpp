// rodlab.Scene and rodlab.SceneError: scenes loaded, overridden and checked as by the command
// line (docs/python.md).
#include "bindings.hpp"

#include "errors.hpp"

namespace rodlab::python {
namespace {

/// A Python value as the YAML text of a --set override (numbers exactly, lists as flow lists).
std::string yaml_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return py::repr(value).cast<std::string>();
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

void bind_errors(py::module_& m) {
  static py::exception<io::SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::SceneError& e) {
      py::list diagnostics;
      for (const auto& d : e.diagnostics())
        diagnostics.append(py::dict(py::arg("file") = d.source, py::arg("line") = d.line,
                                    py::arg("column") = d.column, py::arg("field") = d.field,
                                    py::arg("message") = d.message));
      py::object error = py::reinterpret_borrow<py::object>(scene_error.ptr())(e.what());
      error.attr("diagnostics") = diagnostics;
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    } catch (const cli::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}
}  // namespace

void PyScene::reload() {
  scene = path ? io::load_scene(*path, overrides)
               : io::load_scene_from_string(text, name, overrides);
}

void bind_scene(py::module_& m) {
  bind_errors(m);
  py::class_<PyScene>(m, "Scene", "A checked scene (docs/scene-reference.md)")
      .def_static(
          "load",
          [](const std::string& path) {
            PyScene s;
            s.path = path;
            s.reload();
            return s;
          },
          py::arg("path"), "Reads and checks a scene file; raises SceneError")
      .def_static(
          "from_yaml",
          [](const std::string& text, const std::string& name) {
            PyScene s;
            s.text = text;
            s.name = name;
            s.reload();
            return s;
          },
          py::arg("text"), py::arg("name") = "<yaml>", "A scene from YAML text")
      .def(
          "set",
          [](PyScene& s, const std::string& key, const py::object& value) {
            PyScene changed = s;
            changed.overrides.push_back(io::parse_override(key + "=" + yaml_text(value)));
            changed.reload();  // raises SceneError, leaving the scene as it was
            s = std::move(changed);
          },
          py::arg("key"), py::arg("value"),
          "Overrides a field by its dotted path, as --set KEY=VALUE; raises SceneError")
      .def_property_readonly("name", [](const PyScene& s) { return s.scene.name; })
      .def_property_readonly("length", [](const PyScene& s) { return s.scene.rod.length; })
      .def_property_readonly("actuator_count",
                             [](const PyScene& s) { return s.scene.actuators.size(); });
}
}  // namespace rodlab::python
