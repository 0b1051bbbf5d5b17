// The Python module `rodlab` (issue #16; docs/python.md): scenes, statics, dynamics and a
// stepping plant from Python, built from the same libraries as the command line. A solve takes
// its options the way `rodlab static` / `rodlab dynamic` do (apps/rodlab/common_options.hpp:
// the keyword arguments are the command line's options, resolved over the scene by the same
// code), so the same scene and options give the command line's result to the last bit.
//
// Arrays: a result's arrays are NumPy views of memory the result object owns (no copy); each
// view keeps its result alive (NumPy's base object), so a view may outlive the name bound to
// the result.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/control/plant.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/registry.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"
#include "studies/convergence.hpp"
#include "studies/executor.hpp"
#include "studies/settings.hpp"

#include "common_options.hpp"
#include "errors.hpp"

namespace py = pybind11;
using namespace rodlab;

namespace {

using RowMatrix3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrix6 = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

/// A scene as loaded: its source (a file, or YAML text and a name) and the overrides set on it.
struct PyScene {
  std::optional<std::string> path;
  std::string text, name;
  std::vector<io::Override> overrides;
  scene::Scene scene;

  void reload() {
    scene = path ? io::load_scene(*path, overrides)
                 : io::load_scene_from_string(text, name, overrides);
  }
};

/// A Python value as the YAML text of a --set override (numbers exactly, lists as flow lists).
std::string yaml_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return py::repr(value).cast<std::string>();
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

/// A centreline as arrays, base first: s (N), positions (N x 3), rotations (N x 3 x 3, the
/// columns are the frame d1, d2, d3), twists (N x 6, [kappa; nu]).
struct Centerline {
  Eigen::VectorXd s;
  RowMatrix3 positions;
  std::vector<double> rotations;
  RowMatrix6 twists;

  explicit Centerline(const std::vector<result::CenterlineSample>& c)
      : s(c.size()), positions(c.size(), 3), rotations(9 * c.size()), twists(c.size(), 6) {
    for (std::size_t j = 0; j < c.size(); ++j) {
      s[j] = c[j].s;
      positions.row(j) = c[j].pose.translation().transpose();
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rotations.data() + 9 * j) =
          c[j].pose.rotation_matrix();
      twists.row(j) = c[j].twist.transpose();
    }
  }
};

py::array rotations_view(const Centerline& c, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(c.s.size());
  return py::array_t<double>({n, py::ssize_t{3}, py::ssize_t{3}},
                             {py::ssize_t{72}, py::ssize_t{24}, py::ssize_t{8}},
                             c.rotations.data(), owner);
}

struct PyStaticResult {
  result::StaticResult r;
  Centerline centerline;
  explicit PyStaticResult(result::StaticResult in) : r(std::move(in)), centerline(r.centerline) {}
};

struct PyDynamicResult {
  result::DynamicResult r;
  Centerline final_centerline;
  Eigen::VectorXd t;
  RowMatrix3 tip;
  std::vector<std::pair<std::string, Eigen::VectorXd>> energy;
  explicit PyDynamicResult(result::DynamicResult in)
      : r(std::move(in)), final_centerline(r.final_centerline),
        t(Eigen::Map<const Eigen::VectorXd>(r.t.data(), static_cast<Eigen::Index>(r.t.size()))),
        tip(r.tip_position.size(), 3) {
    for (std::size_t k = 0; k < r.tip_position.size(); ++k) tip.row(k) = r.tip_position[k];
    const auto& e = r.energy;
    for (const auto& [name, v] : {std::pair{"kinetic", &e.kinetic}, {"strain", &e.strain},
                                  {"gravity", &e.gravity}, {"dissipated", &e.dissipated},
                                  {"work_in", &e.work_in}, {"total", &e.total}})
      energy.emplace_back(name, Eigen::Map<const Eigen::VectorXd>(
                                    v->data(), static_cast<Eigen::Index>(v->size())));
  }
};

/// The command line's options from keyword arguments (None: not given).
cli::SolveOptions solve_options(const PyScene& s, solvers::Problem problem, const char* command,
                                const std::optional<std::string>& scheme,
                                std::optional<int> nodes, std::optional<double> tol) {
  cli::SolveOptions o;
  o.scene_path = s.path.value_or(s.name);
  o.overrides = s.overrides;
  if (scheme) {
    std::string why;
    o.scheme = cli::fitting_scheme(*scheme, problem, command, why);
    if (!o.scheme) throw py::value_error("scheme: " + why);
  }
  o.nodes = nodes;
  o.tol = tol;
  return o;
}

PyStaticResult solve_static(const PyScene& s, const std::optional<std::string>& scheme,
                            std::optional<int> nodes, std::optional<double> tol,
                            std::optional<double> time) {
  cli::SolveOptions o = solve_options(s, solvers::Problem::statics, "static", scheme, nodes, tol);
  o.time = time;
  const cli::StaticRun run = cli::resolve_static_run(o, s.scene, "static");
  py::gil_scoped_release unlocked;
  return PyStaticResult(solvers::statics::solve_static(s.scene, run.solve));
}

PyDynamicResult solve_dynamic(const PyScene& s, const std::optional<std::string>& scheme,
                              std::optional<int> nodes, std::optional<double> tol,
                              const py::object& dt, std::optional<double> t_end,
                              std::optional<int> output_every) {
  cli::SolveOptions o = solve_options(s, solvers::Problem::dynamics, "dynamic", scheme, nodes, tol);
  if (!dt.is_none()) {
    if (py::isinstance<py::str>(dt) && dt.cast<std::string>() == "auto")
      o.dt = cli::TimeStep{true, 0.0};
    else
      o.dt = cli::TimeStep{false, dt.cast<double>()};
  }
  o.t_end = t_end;
  o.output_every = output_every;
  cli::DynamicRun run = cli::resolve_dynamic_run(o, s.scene, "dynamic");
  cli::resolve_time_step(run, s.scene);
  py::gil_scoped_release unlocked;
  return PyDynamicResult(solvers::dynamics::solve_dynamic(s.scene, run.solve));
}

/// A NumPy view of an Eigen member (a vector, or a row-major matrix) that keeps `self` alive.
template <class T, class M>
auto view(M T::*member) {
  return [member](py::object self) {
    const auto& m = self.cast<const T&>().*member;
    std::vector<py::ssize_t> shape{m.rows()};
    if constexpr (M::ColsAtCompileTime != 1) shape.push_back(m.cols());
    return py::array_t<double>(shape, m.data(), self);
  };
}

/// `rodlab study convergence|work-precision` in process: study.json (rodlab.study/1) as Python
/// objects. The problem class follows from the schemes (statics without them), as on the
/// command line.
py::object study(const PyScene& s, const std::string& kind,
                 const std::optional<std::vector<std::string>>& schemes,
                 const std::optional<std::vector<int>>& nodes,
                 const std::optional<std::vector<double>>& dts, std::optional<double> t_end,
                 const std::optional<std::string>& reference, std::optional<double> tol,
                 std::optional<int> repeats, int jobs) {
  namespace study = validation::study;
  if (kind != "convergence" && kind != "work-precision")
    throw py::value_error("kind: convergence or work-precision (got " + kind + ")");
  study::Settings settings;
  settings.scene_path = s.path.value_or(s.name);
  for (const auto& o : s.overrides) settings.overrides.push_back(o.text);
  settings.scene = s.scene;
  for (const auto& name : schemes.value_or(std::vector<std::string>{})) {
    const auto scheme = solvers::find_scheme(name);
    if (!scheme) throw py::value_error("schemes: unknown scheme '" + name + "'");
    if (!settings.schemes.empty() && scheme->problem != settings.problem)
      throw py::value_error("schemes: statics and dynamics schemes mixed");
    settings.problem = scheme->problem;
    settings.schemes.push_back(*scheme);
  }
  if (settings.schemes.empty()) settings.schemes = study::schemes_of(settings.problem);
  settings.nodes = nodes.value_or(std::vector<int>{});
  settings.dts = dts.value_or(std::vector<double>{});
  settings.reference = reference;
  settings.tol = tol.value_or(s.scene.solver.tol);
  settings.repeats = kind == "work-precision" ? repeats.value_or(5) : 1;
  settings.command_line = "rodlab.study(" + kind + ")";
  if (settings.problem == solvers::Problem::dynamics) {
    const auto scene_t_end = s.scene.dynamics ? s.scene.dynamics->t_end : std::nullopt;
    if (!t_end && !scene_t_end)
      throw py::value_error("t_end: no run length; give t_end or set dynamics.t_end");
    settings.t_end = t_end ? *t_end : *scene_t_end;
  }
  study::Json json;
  {
    py::gil_scoped_release unlocked;
    const study::Sweep sweep = study::run_sweep(settings, study::Executor{jobs, nullptr, {}});
    json = study::sweep_json(sweep, settings, kind);
  }
  return py::module_::import("json").attr("loads")(json.dump());
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

void bind_scene(py::module_& m) {
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

void bind_results(py::module_& m) {
  py::class_<Centerline>(m, "Centerline")
      .def_property_readonly("s", view(&Centerline::s))
      .def_property_readonly("positions", view(&Centerline::positions))
      .def_property_readonly("rotations",
                             [](py::object self) { return rotations_view(self.cast<const Centerline&>(), self); })
      .def_property_readonly("twists", view(&Centerline::twists));
  py::class_<PyStaticResult>(m, "StaticResult")
      .def_property_readonly("scheme", [](const PyStaticResult& r) { return r.r.scheme; })
      .def_property_readonly("nodes", [](const PyStaticResult& r) { return r.r.nodes; })
      .def_property_readonly("converged", [](const PyStaticResult& r) { return r.r.converged; })
      .def_property_readonly("reason", [](const PyStaticResult& r) { return r.r.reason; })
      .def_property_readonly("iterations", [](const PyStaticResult& r) { return r.r.iterations; })
      .def_property_readonly("residual_norm",
                             [](const PyStaticResult& r) { return r.r.residual_norm; })
      .def_property_readonly("wall_time_s", [](const PyStaticResult& r) { return r.r.wall_time_s; })
      .def_property_readonly("base_wrench",
                             [](const PyStaticResult& r) { return Eigen::VectorXd(r.r.base_wrench); })
      .def_property_readonly("centerline", [](py::object self) {
        return py::cast(&self.cast<PyStaticResult&>().centerline,
                        py::return_value_policy::reference_internal, self);
      });
  py::class_<PyDynamicResult>(m, "DynamicResult")
      .def_property_readonly("scheme", [](const PyDynamicResult& r) { return r.r.scheme; })
      .def_property_readonly("nodes", [](const PyDynamicResult& r) { return r.r.nodes; })
      .def_property_readonly("dt", [](const PyDynamicResult& r) { return r.r.dt; })
      .def_property_readonly("steps", [](const PyDynamicResult& r) { return r.r.steps; })
      .def_property_readonly("converged", [](const PyDynamicResult& r) { return r.r.converged; })
      .def_property_readonly("reason", [](const PyDynamicResult& r) { return r.r.reason; })
      .def_property_readonly("wall_time_s", [](const PyDynamicResult& r) { return r.r.wall_time_s; })
      .def_property_readonly("t", view(&PyDynamicResult::t))
      .def_property_readonly("tip_position", view(&PyDynamicResult::tip))
      .def_property_readonly("energy",
                             [](py::object self) {
                               py::dict out;
                               for (const auto& [name, v] : self.cast<const PyDynamicResult&>().energy)
                                 out[py::str(name)] = py::array_t<double>({v.size()}, v.data(), self);
                               return out;
                             })
      .def_property_readonly("final_centerline", [](py::object self) {
        return py::cast(&self.cast<PyDynamicResult&>().final_centerline,
                        py::return_value_policy::reference_internal, self);
      });
}

/// A dynamics scheme stepped from Python with the scene's own loads and schedules (any scheme,
/// any scene; the Plant is the one with inputs set from Python): the time loop of
/// solve_dynamic, one step per call.
class Simulation {
 public:
  Simulation(const PyScene& s, const std::optional<std::string>& scheme, std::optional<int> nodes,
             const py::object& dt)
      : scene_(s.scene) {
    cli::SolveOptions o =
        solve_options(s, solvers::Problem::dynamics, "dynamic", scheme, nodes, std::nullopt);
    options_ = cli::resolve_dynamic_solver(o, scene_, cli::scene_dynamics_scheme(scene_), "dynamic")
                   .solve;
    problem_ = std::make_unique<solvers::dynamics::DynamicProblem>(
        solvers::dynamics::DynamicProblem::from_scene(scene_));
    const auto scene_dt = scene_.dynamics ? scene_.dynamics->dt : std::nullopt;
    if (!dt.is_none())
      dt_ = dt.cast<double>();
    else if (scene_dt)
      dt_ = *scene_dt;
    else
      dt_ = solvers::dynamics::auto_time_step(*problem_, options_.scheme, options_.nodes);
    if (!(dt_ > 0.0)) throw py::value_error("dt must be > 0");
    options_.dt = dt_;
    // refused up front where single shooting cannot converge, as solve_dynamic does
    const auto id = solvers::scheme_for(options_.scheme, solvers::Problem::dynamics).id;
    if (id == solvers::SchemeId::implicit_midpoint || id == solvers::SchemeId::bdf_alpha)
      if (const std::string why = solvers::dynamics::single_shooting_step_problem(
              *problem_, options_.scheme, options_.grid, dt_, options_.tol);
          !why.empty())
        throw py::value_error(why);
    std::string failure;
    const auto initial = solvers::dynamics::initial_state(scene_, *problem_, options_, failure);
    if (!failure.empty()) throw std::runtime_error("the initial state: " + failure);
    stepper_ = solvers::stepper_factory(id)(*problem_, options_, initial);
  }

  /// One step of dt (the time before it is steps x dt, as in solve_dynamic).
  void step() {
    solvers::dynamics::StepStatus status;
    {
      py::gil_scoped_release unlocked;
      status = stepper_->step(static_cast<double>(steps_) * dt_, dt_);
    }
    if (!status.ok) throw std::runtime_error("the step failed: " + status.reason);
    ++steps_;
  }

  double time() const { return static_cast<double>(steps_) * dt_; }
  double dt() const { return dt_; }
  const std::string& scheme() const { return options_.scheme; }
  const solvers::dynamics::Stepper& stepper() const { return *stepper_; }

 private:
  scene::Scene scene_;
  solvers::dynamics::DynamicSolveOptions options_;
  std::unique_ptr<solvers::dynamics::DynamicProblem> problem_;  // the stepper refers to it
  std::unique_ptr<solvers::dynamics::Stepper> stepper_;
  double dt_ = 0.0;
  long steps_ = 0;
};

/// The current state of a stepper as a dict of arrays and energies.
py::dict state_of(const solvers::dynamics::Stepper& stepper) {
  const auto e = stepper.energy();
  const auto eta = stepper.velocities();
  RowMatrix6 v(eta.size(), 6);
  for (std::size_t j = 0; j < eta.size(); ++j) v.row(j) = eta[j].transpose();
  return py::dict(py::arg("centerline") = Centerline(stepper.centerline()),
                  py::arg("velocities") = Eigen::MatrixXd(v),
                  py::arg("energy") = py::dict(py::arg("kinetic") = e.kinetic,
                                               py::arg("strain") = e.strain,
                                               py::arg("gravity") = e.gravity,
                                               py::arg("dissipated") = e.dissipated,
                                               py::arg("work_in") = e.work_in,
                                               py::arg("total") = e.total()));
}

void bind_simulation(py::module_& m) {
  py::class_<Simulation>(m, "Simulation",
                         "A dynamics scheme stepped one step at a time under the scene's own "
                         "loads and schedules")
      .def(py::init<const PyScene&, const std::optional<std::string>&, std::optional<int>,
                    const py::object&>(),
           py::arg("scene"), py::kw_only(), py::arg("scheme") = py::none(),
           py::arg("nodes") = py::none(), py::arg("dt") = py::none())
      .def("step", &Simulation::step, "One step of dt; raises RuntimeError when it fails")
      .def_property_readonly("time", &Simulation::time)
      .def_property_readonly("dt", &Simulation::dt)
      .def_property_readonly("scheme", &Simulation::scheme)
      .def_property_readonly("tip", [](const Simulation& s) {
        return Eigen::Vector3d(s.stepper().tip_position());
      })
      .def("state", [](const Simulation& s) { return state_of(s.stepper()); },
           "centerline, velocities (N x 6, [omega; v], body frame) and energies");
}

void bind_plant(py::module_& m) {
  using solvers::control::Plant;
  py::class_<Plant>(m, "Plant",
                    "A dynamics scheme stepped one control step at a time with held inputs "
                    "(docs/control.md \"The plant\")")
      .def(py::init([](const PyScene& s, const std::optional<std::string>& scheme,
                       std::optional<int> nodes, double dt_control) {
             cli::SolveOptions o =
                 solve_options(s, solvers::Problem::dynamics, "control", scheme, nodes, std::nullopt);
             solvers::control::PlantOptions p;
             p.solver = cli::resolve_plant_solver(o, s.scene, "control");
             p.solver.max_iterations =
                 std::max(p.solver.max_iterations, solvers::control::PlantOptions::kShotsPerStep);
             p.dt_control = dt_control;
             return std::make_unique<Plant>(s.scene, p);
           }),
           py::arg("scene"), py::arg("scheme") = py::none(), py::arg("nodes") = py::none(),
           py::arg("dt_control") = 0.05)
      .def_property_readonly("time", &Plant::time)
      .def_property_readonly("dt_control", &Plant::dt_control)
      .def_property_readonly("lower", [](const Plant& p) { return Eigen::VectorXd(p.lower()); })
      .def_property_readonly("upper", [](const Plant& p) { return Eigen::VectorXd(p.upper()); })
      .def_property_readonly("tip", [](const Plant& p) { return Eigen::Vector3d(p.tip()); })
      .def("set_input", [](Plant& p, const Eigen::VectorXd& u) { p.set_input(u); },
           py::arg("u"), "The actuator inputs held over the next control step")
      .def(
          "step",
          [](Plant& p) {
            solvers::dynamics::StepStatus status;
            {
              py::gil_scoped_release unlocked;
              status = p.advance();
            }
            if (!status.ok) throw std::runtime_error("the plant's step failed: " + status.reason);
          },
          "Advances one control step; raises RuntimeError when the step fails")
      .def("centerline", [](const Plant& p) { return Centerline(p.stepper().centerline()); });
}

}  // namespace

PYBIND11_MODULE(rodlab, m) {
  m.doc() = "rodlab: Cosserat and Kirchhoff rods (docs/python.md)";
  bind_errors(m);
  bind_scene(m);
  bind_results(m);
  bind_plant(m);
  bind_simulation(m);
  m.def(
      "schemes",
      [] {
        py::list out;
        for (const auto& s : solvers::all_schemes())
          out.append(py::dict(py::arg("name") = std::string(s.name),
                              py::arg("problem") = std::string(solvers::to_string(s.problem)),
                              py::arg("order") = std::string(s.order),
                              py::arg("implicit") = s.implicit,
                              py::arg("reference") = s.reference,
                              py::arg("method") = std::string(s.method)));
        return out;
      },
      "Every scheme, as `rodlab schemes` lists them");
  m.def("study", &study, py::arg("scene"), py::arg("kind"), py::kw_only(),
        py::arg("schemes") = py::none(), py::arg("nodes") = py::none(),
        py::arg("dts") = py::none(), py::arg("t_end") = py::none(),
        py::arg("reference") = py::none(), py::arg("tol") = py::none(),
        py::arg("repeats") = py::none(), py::arg("jobs") = 1,
        "A convergence or work-precision study, as `rodlab study`: its study.json");
  m.def("solve_static", &solve_static, py::arg("scene"), py::kw_only(),
        py::arg("scheme") = py::none(), py::arg("nodes") = py::none(), py::arg("tol") = py::none(),
        py::arg("time") = py::none(), "Static equilibrium, as `rodlab static`");
  m.def("solve_dynamic", &solve_dynamic, py::arg("scene"), py::kw_only(),
        py::arg("scheme") = py::none(), py::arg("nodes") = py::none(), py::arg("tol") = py::none(),
        py::arg("dt") = py::none(), py::arg("t_end") = py::none(),
        py::arg("output_every") = py::none(), "Time simulation, as `rodlab dynamic`");
}
