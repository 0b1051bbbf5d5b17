// rodlab.Simulation and rodlab.Plant: dynamics stepped from Python, under the scene's own loads
// (any scheme) or with actuator inputs set between control steps (docs/python.md).
#include "bindings.hpp"

#include "rodlab/solvers/control/plant.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/registry.hpp"

namespace rodlab::python {
namespace {

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
        solvers::dynamics::problem_on_grid(
            solvers::dynamics::DynamicProblem::from_scene(scene_), options_));
    const auto scene_dt = scene_.dynamics ? scene_.dynamics->dt : std::nullopt;
    if (!dt.is_none())
      dt_ = dt.cast<double>();
    else if (scene_dt)
      dt_ = *scene_dt;
    else
      dt_ = solvers::dynamics::auto_time_step(*problem_, options_.scheme, options_.nodes);
    if (!(dt_ > 0.0)) throw py::value_error("dt must be > 0");
    options_.dt = dt_;
    // refused up front where shooting cannot converge, as solve_dynamic does
    if (const std::string why = solvers::dynamics::step_problem(*problem_, options_, dt_);
        !why.empty())
      throw py::value_error(why);
    const auto id = solvers::scheme_for(options_.scheme, solvers::Problem::dynamics).id;
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

void bind_stepping(py::module_& m) {
  bind_simulation(m);
  bind_plant(m);
}

}  // namespace rodlab::python
