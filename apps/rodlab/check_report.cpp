#include "check_report.hpp"

#include "rodlab/io/text_format.hpp"
#include "rodlab/rod/section.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/schemes.hpp"

#include "common_options.hpp"
#include "overloaded.hpp"

namespace rodlab::cli {
namespace {

std::vector<double> to_std(const Eigen::Ref<const Eigen::VectorXd>& v) {
  return {v.data(), v.data() + v.size()};
}

std::string with_unit(const std::string& value, const std::string& unit) {
  return unit.empty() ? value : value + " " + unit;
}

// --- describing scene inputs in words -------------------------------------------------------

std::string value_text(double v) { return io::format_number(v); }
std::string value_text(const Eigen::Vector3d& v) { return io::format_vector(v); }

/// "0.5 N", or "steps: 0 N at t = 0 s, 0.5 N at t = 1 s" (long schedules summarised).
template <class Value>
std::string describe(const scene::Schedule<Value>& schedule, const std::string& unit) {
  using Kind = typename scene::Schedule<Value>::Kind;
  const auto& points = schedule.points();
  if (schedule.is_constant()) return with_unit(value_text(points.front().second), unit);
  const std::string kind = schedule.kind() == Kind::steps ? "steps" : "ramp";
  if (points.size() > 4)
    return kind + " of " + std::to_string(points.size()) + " points from " +
           with_unit(value_text(points.front().second), unit) +
           " at t = " + io::format_number(points.front().first) + " s to " +
           with_unit(value_text(points.back().second), unit) +
           " at t = " + io::format_number(points.back().first) + " s";
  std::string out = kind + ":";
  for (std::size_t i = 0; i < points.size(); ++i)
    out += (i ? ", " : " ") + with_unit(value_text(points[i].second), unit) +
           " at t = " + io::format_number(points[i].first) + " s";
  return out;
}

std::string describe(const scene::Offset& offset) {
  if (offset.points.size() == 1)
    return "offset " + io::format_vector(offset.points.front().second) + " m";
  return "offset routed through " + std::to_string(offset.points.size()) + " points over s in [" +
         io::format_number(offset.points.front().first) + ", " +
         io::format_number(offset.points.back().first) + "] m";
}

std::string describe_extent(const std::optional<scene::Span>& span,
                            const std::optional<std::pair<double, double>>& limits,
                            const std::string& unit) {
  std::string out;
  if (span) out += ", on s in [" + io::format_number(span->s0) + ", " + io::format_number(span->s1) + "] m";
  if (limits)
    out += ", limits [" + io::format_number(limits->first) + ", " + io::format_number(limits->second) +
           "]" + (unit.empty() ? "" : " " + unit);
  return out;
}

std::string describe(const rod::Circle& c) {
  return "circle, diameter " + io::format_number(c.diameter) + " m";
}
std::string describe(const rod::Tube& t) {
  return "tube, outer diameter " + io::format_number(t.outer_diameter) + " m, inner diameter " +
         io::format_number(t.inner_diameter) + " m";
}
std::string describe(const rod::Rectangle& r) {
  return "rectangle, width " + io::format_number(r.width) + " m (x), height " +
         io::format_number(r.height) + " m (y)";
}
std::string describe(const rod::Section& section) {
  return std::visit([](const auto& shape) { return describe(shape); }, section);
}

std::string describe(const scene::Cable& c) {
  std::string out = "cable, " + describe(c.offset) + ", ";
  out += c.tension ? "tension " + describe(*c.tension, "N")
                   : "displacement " + describe(*c.displacement, "m");
  return out + describe_extent(c.span, c.limits, c.tension ? "N" : "m");
}
std::string describe(const scene::Fluidic& f) {
  std::string out = "fluidic, " + describe(f.offset) + ", chamber radius " +
                    io::format_number(f.chamber_radius) + " m, ";
  out += f.pressure ? "pressure " + describe(*f.pressure, "Pa")
                    : "volume " + describe(*f.volume, "m^3");
  return out + describe_extent(f.span, f.limits, f.pressure ? "Pa" : "m^3");
}
std::string describe(const scene::Muscle& m) {
  return "muscle, " + describe(m.offset) + ", section " + describe(m.section) + ", E " +
         io::format_number(m.material.E) + " Pa, input " + describe(m.input, "") + ", law " +
         m.law.type + " (gain " + io::format_number(m.law.gain) + " N, stiffness " +
         io::format_number(m.law.stiffness) + " N)" + describe_extent(m.span, m.limits, "");
}
std::string describe(const scene::Actuator& actuator) {
  return std::visit([](const auto& a) { return describe(a); }, actuator);
}

std::string describe(const lie::SE3& pose) {
  const bool at_origin = pose.translation().isZero(0.0);
  const lie::Matrix3 R = pose.rotation_matrix();
  const bool unrotated = R.isIdentity(0.0);
  if (at_origin && unrotated) return "identity";
  const std::string rotation = unrotated ? std::string("identity")
                                         : "[" + io::format_vector(R.row(0).transpose()) + ", " +
                                               io::format_vector(R.row(1).transpose()) + ", " +
                                               io::format_vector(R.row(2).transpose()) + "]";
  return "position " + io::format_vector(pose.translation()) + " m, rotation " + rotation;
}

std::string frame_name(scene::Frame frame) {
  return frame == scene::Frame::body ? "body" : "world";
}

// --- sections -------------------------------------------------------------------------------

ReportSection scene_section(const scene::Scene& scene) {
  const bool kirchhoff = scene.rod.model == rod::ModelKind::kirchhoff;
  ReportSection s{"scene", "Scene", {}};
  s.items.push_back({"name", "name", "", scene.name, ""});
  s.items.push_back({"file", "file", "", scene.source_path, ""});
  s.items.push_back({"model", "model", "", std::string(kirchhoff ? "kirchhoff" : "cosserat"), ""});
  s.items.push_back(
      {"strains", "free strains", "",
       std::string(kirchhoff ? "bending and torsion; shear and extension held at nu* (3.45)"
                             : "all six: bending, torsion, shear, extension"),
       ""});
  s.items.push_back({"length", "length", "L", scene.rod.length, "m"});
  if (scene.rod.rest_spans.empty()) {
    s.items.push_back(
        {"reference_twist", "reference twist", "xi*", to_std(scene.rod.reference_twist), ""});
  } else {
    for (std::size_t k = 0; k < scene.rod.rest_spans.size(); ++k) {
      const auto& span = scene.rod.rest_spans[k];
      const std::string n = std::to_string(k + 1);
      s.items.push_back({"rest_span_" + n + "_begin", "rest span " + n + " begins at", "s",
                         span.begin, "m"});
      s.items.push_back({"rest_span_" + n + "_strain", "rest span " + n + " strain", "xi*",
                         to_std(span.xi_star), ""});
    }
  }
  s.items.push_back({"base", "base pose", "", describe(scene.base.pose), ""});
  if (const auto* clamped = std::get_if<scene::ClampedTip>(&scene.tip)) {
    s.items.push_back({"tip", "tip", "", "clamped at " + describe(clamped->pose), ""});
  } else {
    const auto& w = std::get<scene::FreeTip>(scene.tip).wrench;
    const auto is_zero = [](const scene::VectorSchedule& v) {
      return v.is_constant() && v.points().front().second.isZero(0.0);
    };
    s.items.push_back({"tip", "tip", "",
                       is_zero(w.moment) && is_zero(w.force)
                           ? std::string("free, no tip wrench")
                           : "free; moment " + describe(w.moment, "N m") + ", force " +
                                 describe(w.force, "N") + ", " + frame_name(w.frame) + " frame",
                       ""});
  }
  return s;
}

ReportSection section_section(const scene::Scene& scene, const rod::Characteristics& c) {
  const auto& p = c.section;
  ReportSection s{"section", "Cross-section: " + describe(scene.rod.section), {}};
  s.items.push_back({"shape", "shape", "", std::string(rod::shape_name(scene.rod.section)), ""});
  std::visit(
      Overloaded{
          [&](const rod::Circle& x) {
            s.items.push_back({"diameter", "diameter", "D", x.diameter, "m"});
          },
          [&](const rod::Tube& x) {
            s.items.push_back({"outer_diameter", "outer diameter", "Do", x.outer_diameter, "m"});
            s.items.push_back({"inner_diameter", "inner diameter", "Di", x.inner_diameter, "m"});
          },
          [&](const rod::Rectangle& x) {
            s.items.push_back({"width", "width (along x)", "w", x.width, "m"});
            s.items.push_back({"height", "height (along y)", "h", x.height, "m"});
          },
      },
      scene.rod.section);
  s.items.push_back({"A", "area", "A", p.A, "m^2"});
  s.items.push_back({"Ix", "second moment about x", "Ix", p.Ix, "m^4"});
  s.items.push_back({"Iy", "second moment about y", "Iy", p.Iy, "m^4"});
  s.items.push_back({"J", "polar moment", "J", p.J, "m^4"});
  s.items.push_back({"Jt", "torsion constant", "Jt", p.Jt, "m^4"});
  return s;
}

ReportSection material_section(const scene::Scene& scene) {
  const auto& m = scene.rod.material;
  return {"material",
          "Material",
          {{"E", "Young's modulus", "E", m.E, "Pa"},
           {"G", "shear modulus", "G", m.G, "Pa"},
           {"poisson", "Poisson's ratio", "E/(2G) - 1", m.poisson(), ""},
           {"rho", "density", "rho", m.rho, "kg/m^3"},
           {"viscosity", "Kelvin-Voigt viscosity", "alpha", m.viscosity, "Pa s"}}};
}

ReportSection matrices_section(const rod::Characteristics& c, bool viscous) {
  ReportSection s{"matrices",
                  std::string("Stiffness K (2.28), inertia M (3.5)") +
                      (viscous ? ", viscosity V (3.10)" : "") + ": diagonals, order [omega; nu]",
                  {}};
  const std::vector<std::string> strains{"bending about x", "bending about y", "torsion",
                                         "shear along x",   "shear along y",   "extension"};
  s.items.push_back({"K_diag",
                     "",
                     "K",
                     to_std(c.K_diag),
                     "",
                     strains,
                     {"E Ix", "E Iy", "G Jt", "G A", "G A", "E A"},
                     {"N m^2", "N m^2", "N m^2", "N", "N", "N"}});
  s.items.push_back({"M_diag",
                     "",
                     "M",
                     to_std(c.M_diag),
                     "",
                     {"rotary inertia x", "rotary inertia y", "rotary inertia z", "mass per length",
                      "mass per length", "mass per length"},
                     {"rho Ix", "rho Iy", "rho J", "rho A", "rho A", "rho A"},
                     {"kg m", "kg m", "kg m", "kg/m", "kg/m", "kg/m"}});
  if (viscous)
    s.items.push_back({"V_diag",
                       "",
                       "V",
                       to_std(c.V_diag),
                       "",
                       strains,
                       {"3 alpha Ix", "3 alpha Iy", "alpha J", "alpha A", "alpha A", "3 alpha A"},
                       {"N m^2 s", "N m^2 s", "N m^2 s", "N s", "N s", "N s"}});
  return s;
}

ReportSection time_section(const scene::Scene& scene, const rod::Characteristics& c,
                           const std::string& nodes_from) {
  const double k = c.thesis_safety_factor;
  ReportSection s{
      "time_scales",
      "Waves and time steps for N = " + std::to_string(c.nodes) + " nodes (" + nodes_from + ")",
      {}};
  s.items.push_back(
      {"axial_wave_speed", "axial wave speed", "sqrt(E/rho)", c.axial_wave_speed, "m/s"});
  s.items.push_back(
      {"shear_wave_speed", "shear wave speed", "sqrt(G/rho)", c.shear_wave_speed, "m/s"});
  s.items.push_back({"nodes", "nodes", "N", static_cast<long long>(c.nodes), ""});
  s.items.push_back({"ds", "node spacing", "ds = L/(N-1)", c.ds, "m"});
  s.items.push_back({"dt_cfl", "CFL bound (3.43)", "ds/c_max", c.dt_cfl, "s"});
  s.items.push_back({"dt_thesis", "explicit time step (3.44)", io::format_number(k) + " ds sqrt(rho/E)",
                     c.dt_thesis, "s"});
  s.items.push_back({"thesis_safety_factor", "safety factor (thesis)", "k", k, ""});
  // What `dt: auto` takes (time_step.hpp): (3.44) ignores viscosity and drag, whose relaxation
  // can set a far smaller stable step for `variational` (docs/dynamics.md "Stability").
  try {
    namespace d = solvers::dynamics;
    const auto problem = d::DynamicProblem::from_scene(scene);
    // on the scene's grid (solver.grid: corrected)
    const auto on_grid = d::scene_problem_on_grid(scene, "variational", c.nodes);
    s.items.push_back({"dt_auto_variational", "variational step (dt: auto)",
                       io::format_number(d::kVariationalSafety) +
                           " x stable step (waves, viscosity, drag)",
                       d::auto_time_step(on_grid, "variational", c.nodes), "s"});
    s.items.push_back({"dt_auto_implicit", "implicit step (dt: auto)", "first bending period / 10",
                       d::auto_time_step(problem, "implicit-midpoint", c.nodes), "s"});
  } catch (const std::exception&) {  // a scene the dynamics cannot take: `rodlab dynamic` says why
  }
  return s;
}

ReportSection frequency_section(const scene::Scene& scene, const rod::Characteristics& c) {
  const std::string support = scene.tip_clamped() ? "clamped-clamped" : "clamped-free";
  return {
      "frequencies",
      "First natural frequencies (" + support + "; Euler-Bernoulli bending about the weaker axis)",
      {{"first_bending_hz", "first bending", "f_b", c.first_bending_frequency_hz, "Hz"},
       {"first_axial_hz", "first axial", "f_a", c.first_axial_frequency_hz, "Hz"}}};
}

ReportSection adequacy_section(const scene::Scene& scene, const rod::Characteristics& c) {
  ReportSection s{"model_choice", "Is the Kirchhoff model enough? (shear and extension)", {}};
  s.items.push_back(
      {"shear_to_bending", "shear to bending", "G A L^2/(E I)", c.shear_to_bending, ""});
  s.items.push_back(
      {"axial_to_bending", "axial to bending", "E A L^2/(E I)", c.axial_to_bending, ""});
  s.items.push_back({"kirchhoff_error_estimate", "Kirchhoff error estimate", "3 E I/(G A L^2)",
                     c.kirchhoff_error_estimate, ""});
  s.items.push_back({"kirchhoff_safe", "Kirchhoff safe (< 1 %)", "", c.kirchhoff_safe, ""});
  const std::string percent = io::format_number(100.0 * c.kirchhoff_error_estimate) + " %";
  const bool kirchhoff = scene.rod.model == rod::ModelKind::kirchhoff;
  std::string verdict = "shear adds about " + percent + " to the bending deflection";
  if (c.kirchhoff_safe)
    verdict += kirchhoff ? " (< 1 %): the Kirchhoff model is safe here"
                         : " (< 1 %): a Kirchhoff model would do, with larger explicit steps";
  else
    verdict += kirchhoff ? " (>= 1 %): WARNING, the Kirchhoff model drops it; use model: cosserat"
                         : " (>= 1 %): keep the Cosserat model";
  s.items.push_back({"verdict", "verdict", "", verdict, ""});
  return s;
}

ReportSection loads_section(const scene::Scene& scene) {
  const auto& l = scene.loads;
  std::vector<std::string> loads;
  if (l.gravity) loads.push_back("gravity " + io::format_vector(*l.gravity) + " m/s^2");
  if (l.buoyancy)
    loads.push_back("buoyancy, fluid density " + io::format_number(l.buoyancy->fluid_density) +
                    " kg/m^3");
  if (l.drag)
    loads.push_back("drag, fluid density " + io::format_number(l.drag->fluid_density) +
                    " kg/m^3, laminar " + io::format_vector(l.drag->laminar) + ", turbulent " +
                    io::format_vector(l.drag->turbulent));
  if (l.distributed)
    loads.push_back("distributed wrench, moment " + describe(l.distributed->moment, "N m/m") +
                    ", force " + describe(l.distributed->force, "N/m") + ", " +
                    frame_name(l.distributed->frame) + " frame");
  std::vector<std::string> actuators;
  for (std::size_t i = 0; i < scene.actuators.size(); ++i)
    actuators.push_back(std::to_string(i) + ": " + describe(scene.actuators[i]));
  return {"loads",
          "Loads and actuators",
          {{"loads", "loads", "", loads, ""}, {"actuators", "actuators", "", actuators, ""}}};
}

ReportSection solver_section(const scene::Scene& scene) {
  ReportSection s{"solver", "Solver settings (command-line options win)", {}};
  s.items.push_back({"scheme", "solver.scheme", "", scene.solver.scheme, ""});
  const auto statics = solvers::find_scheme(scene.solver.scheme);
  const bool static_fits = statics && statics->problem == solvers::Problem::statics;
  s.items.push_back({"static_scheme", "`rodlab static` uses", "",
                     static_fits ? scene.solver.scheme
                                 : std::string("--scheme (solver.scheme is not a statics scheme)"),
                     ""});
  s.items.push_back(
      {"dynamic_scheme", "`rodlab dynamic` uses", "", scene_dynamics_scheme(scene), ""});
  s.items.push_back({"nodes", "solver.nodes", "", static_cast<long long>(scene.solver.nodes), ""});
  s.items.push_back({"tol", "solver.tol", "", scene.solver.tol, ""});
  s.items.push_back({"max_iterations", "solver.max_iterations", "",
                     static_cast<long long>(scene.solver.max_iterations), ""});
  if (!scene.dynamics) {
    s.items.push_back(
        {"dynamics", "dynamics", "", std::string("none (`rodlab dynamic` needs --t-end)"), ""});
    return s;
  }
  const auto& d = *scene.dynamics;
  s.items.push_back({"dynamics_scheme", "dynamics.scheme", "", d.scheme.value_or("not set"), ""});
  if (d.t_end)
    s.items.push_back({"t_end", "dynamics.t_end", "", *d.t_end, "s"});
  else
    s.items.push_back({"t_end", "dynamics.t_end", "", std::string("not set (give --t-end)"), ""});
  if (d.dt)
    s.items.push_back({"dt", "dynamics.dt", "", *d.dt, "s"});
  else
    s.items.push_back(
        {"dt", "dynamics.dt", "", std::string("auto (the steps `dt: auto` above)"), ""});
  s.items.push_back({"initial", "dynamics.initial", "",
                     std::string(d.initial == scene::Initial::straight ? "straight" : "static"),
                     ""});
  s.items.push_back(
      {"output_every", "dynamics.output_every", "", static_cast<long long>(d.output_every), ""});
  return s;
}

}  // namespace

Report check_report(const scene::Scene& scene, const rod::Characteristics& c,
                    const std::string& nodes_from) {
  const bool viscous = scene.rod.material.viscosity > 0.0;
  return {kCheckSchema,
          {scene_section(scene), section_section(scene, c), material_section(scene),
           matrices_section(c, viscous), time_section(scene, c, nodes_from), frequency_section(scene, c),
           adequacy_section(scene, c), loads_section(scene), solver_section(scene)}};
}

}  // namespace rodlab::cli
