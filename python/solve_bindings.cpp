// rodlab.solve_static, rodlab.solve_dynamic, rodlab.study and rodlab.schemes: the command
// line's solves and sweep studies, with its options resolved over the scene by the same code
// (apps/rodlab/common_options.hpp), so that they give its results to the last bit.
#include "bindings.hpp"

#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"
#include "studies/convergence.hpp"
#include "studies/executor.hpp"
#include "studies/settings.hpp"

namespace rodlab::python {

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


namespace {

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
  // as the command line without --grids: work-precision sweeps both grids where the scene names
  // none and takes the corrected one (validation/studies/settings.hpp)
  if (kind == "work-precision") settings.grids = study::trade_grids(settings);
  study::Json json;
  {
    py::gil_scoped_release unlocked;
    const study::Sweep sweep = study::run_sweep(settings, study::Executor{jobs, nullptr, {}});
    json = study::sweep_json(sweep, settings, kind);
  }
  return py::module_::import("json").attr("loads")(json.dump());
}
}  // namespace

void bind_solve(py::module_& m) {
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

}  // namespace rodlab::python
