// The "scenes" family of `rodlab validate`: each example scene loads, and the quantities
// `rodlab check` prints for it equal closed forms written out here independently of
// rodlab::rod (section formulas, K = diag(E Ix, E Iy, G Jt, G A, G A, E A) (2.28),
// M = rho diag(Ix, Iy, J, A, A, A) (3.5), V (3.10), wave speeds, (3.44)).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/rod/characteristics.hpp"

#include "checks/check.hpp"

namespace rodlab::validation {
namespace {

constexpr double kRelTol = 1e-12;
constexpr double pi = std::numbers::pi;

/// Section properties in closed form, with the formulas as text.
struct ClosedForm {
  std::string shape;
  double A, Ix, Iy, J;
  std::optional<double> Jt;  ///< rectangles: Saint-Venant series, not a closed form
  std::string fA, fIx, fIy, fJ;
};

ClosedForm closed_form(const rod::Circle& c) {
  const double D = c.diameter, I = pi * std::pow(D, 4) / 64.0;
  return {.shape = "circle",
          .A = pi * D * D / 4.0,
          .Ix = I,
          .Iy = I,
          .J = 2.0 * I,
          .Jt = 2.0 * I,
          .fA = "pi D^2/4",
          .fIx = "pi D^4/64",
          .fIy = "pi D^4/64",
          .fJ = "pi D^4/32"};
}

ClosedForm closed_form(const rod::Tube& t) {
  const double Do = t.outer_diameter, Di = t.inner_diameter;
  const double I = pi * (std::pow(Do, 4) - std::pow(Di, 4)) / 64.0;
  return {.shape = "tube",
          .A = pi * (Do * Do - Di * Di) / 4.0,
          .Ix = I,
          .Iy = I,
          .J = 2.0 * I,
          .Jt = 2.0 * I,
          .fA = "pi (Do^2 - Di^2)/4",
          .fIx = "pi (Do^4 - Di^4)/64",
          .fIy = "pi (Do^4 - Di^4)/64",
          .fJ = "pi (Do^4 - Di^4)/32"};
}

ClosedForm closed_form(const rod::Rectangle& r) {
  const double w = r.width, h = r.height;
  return {.shape = "rectangle",
          .A = w * h,
          .Ix = w * h * h * h / 12.0,
          .Iy = h * w * w * w / 12.0,
          .J = w * h * (w * w + h * h) / 12.0,
          .Jt = std::nullopt,
          .fA = "w h",
          .fIx = "w h^3/12",
          .fIy = "h w^3/12",
          .fJ = "w h (w^2 + h^2)/12"};
}

void add_derived_checks(const std::string& name, const scene::Scene& scene,
                        std::vector<Check>& out) {
  const auto& m = scene.rod.material;
  const double L = scene.rod.length;
  const int N = scene.solver.nodes;
  const auto tip = scene.tip_clamped() ? rod::TipSupport::clamped : rod::TipSupport::free;
  const rod::Characteristics c = rod::characteristics(scene.rod.to_model(), N, tip);
  const ClosedForm f = std::visit([](const auto& x) { return closed_form(x); }, scene.rod.section);
  const auto check = [&](const std::string& what, double measured, double expected,
                         const std::string& formula) {
    out.push_back(
        relative_check(name + ": " + what, measured, expected, kRelTol, "closed form: " + formula));
  };
  // Formulas in the section's dimensions name the shape.
  const auto section_check = [&](const std::string& what, double measured, double expected,
                                 const std::string& formula) {
    check(what, measured, expected, formula + " (" + f.shape + ")");
  };

  section_check("A", c.section.A, f.A, f.fA);
  section_check("K[0] = E Ix", c.K_diag[0], m.E * f.Ix, "E " + f.fIx);
  section_check("K[1] = E Iy", c.K_diag[1], m.E * f.Iy, "E " + f.fIy);
  if (f.Jt) section_check("K[2] = G Jt", c.K_diag[2], m.G * *f.Jt, "G " + f.fJ);
  section_check("K[3] = G A", c.K_diag[3], m.G * f.A, "G " + f.fA);
  section_check("K[5] = E A", c.K_diag[5], m.E * f.A, "E " + f.fA);
  section_check("M[0] = rho Ix", c.M_diag[0], m.rho * f.Ix, "rho " + f.fIx);
  section_check("M[2] = rho J", c.M_diag[2], m.rho * f.J, "rho " + f.fJ);
  section_check("M[3] = rho A", c.M_diag[3], m.rho * f.A, "rho " + f.fA);
  if (m.viscosity > 0.0) {
    section_check("V[0] = 3 alpha Ix", c.V_diag[0], 3.0 * m.viscosity * f.Ix, "3 alpha " + f.fIx);
    section_check("V[3] = alpha A", c.V_diag[3], m.viscosity * f.A, "alpha " + f.fA);
  }
  check("axial wave speed", c.axial_wave_speed, std::sqrt(m.E / m.rho), "sqrt(E/rho)");
  check("shear wave speed", c.shear_wave_speed, std::sqrt(m.G / m.rho), "sqrt(G/rho)");
  const bool kirchhoff = scene.rod.model == rod::ModelKind::kirchhoff;
  const double k = kirchhoff ? 0.9 : 0.1;  // the thesis' safety factors
  check("explicit time step (3.44)", c.dt_thesis, k * L / (N - 1) * std::sqrt(m.rho / m.E),
        std::string(kirchhoff ? "0.9" : "0.1") + " L/(N-1) sqrt(rho/E), N = " + std::to_string(N));
  const double I_strong = std::max(f.Ix, f.Iy);
  check("Kirchhoff error estimate", c.kirchhoff_error_estimate,
        3.0 * m.E * I_strong / (m.G * f.A * L * L),
        "3 E I/(G A L^2), I = max(Ix, Iy) (" + f.shape + ")");
}

}  // namespace

std::vector<Check> scene_checks(const ValidationContext& context) {
  const std::string loads_reference = "loads and checks without a diagnostic";
  std::vector<Check> out;
  for (const auto& path : scene_files(context.scenes_dir)) {
    const std::string name = path.stem().string();
    std::optional<scene::Scene> scene;
    try {
      scene = io::load_scene(path.string());
    } catch (const std::exception& e) {  // io::SceneError: what() lists every diagnostic
      out.push_back(boolean_check("scene " + name + " loads", false, loads_reference, e.what()));
      continue;
    }
    out.push_back(boolean_check("scene " + name + " loads", true, loads_reference));
    try {
      add_derived_checks(name, *scene, out);
    } catch (const std::exception& e) {
      out.push_back(boolean_check(name + ": derived quantities", false,
                                  "computed without an exception", e.what()));
    }
  }
  return out;
}

}  // namespace rodlab::validation
