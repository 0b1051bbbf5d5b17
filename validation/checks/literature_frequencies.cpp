// Natural frequencies from free vibration (literature_frequencies.hpp). The rod is held by a
// small tip load until t = 1e-9 s and released from that static equilibrium; the motion stays
// linear (tip deflection 3e-4 L, strains 1e-4). Each kind of motion gets its own run and signal:
//   bending  tip force P L^2 / EI = 1e-3 along x    the tip's x, 0.5 s (2.2 fundamental periods)
//   torsion  tip moment M L / G J = 1e-4 about z    the kinetic energy, 0.1 s: the modes are
//            mass-orthogonal, so T(t) = sum_n E_n sin^2(omega_n t) holds 2 f_n and no cross terms
//   axial    tip force F / E A = 1e-4 along z       the tip's z, 0.1 s
// and the matrix pencil (signal_components.hpp) reads the frequencies off it.
#include "checks/literature_frequencies.hpp"

#include <cmath>
#include <string>

#include "rodlab/io/text_format.hpp"

#include "checks/dynamics_runs.hpp"
#include "checks/signal_components.hpp"
#include "reference/cantilever_frequencies.hpp"
#include "reference/reference_rods.hpp"

namespace rodlab::validation {
namespace {

using reference::Table21;

/// The Table 2.1 cantilever held by a world tip force and moment until t = 1e-9 s.
scene::Scene released(const std::string& name, const std::string& force,
                      const std::string& moment) {
  const auto step = [](const std::string& v) {
    return "{steps: [[0, " + v + "], [1.0e-9, [0, 0, 0]]]}";
  };
  return dynamics::rod_scene(name, "{}",
                             "{wrench: {force: " + step(force) + ", moment: " + step(moment) +
                                 ", frame: world}}",
                             0.0);
}

std::string vector_text(double x, double y, double z) {
  return io::format_vector(Eigen::Vector3d(x, y, z));
}

/// One measured mode against its reference.
struct Mode {
  std::string name;
  double reference_hz;
  double euler_bernoulli_hz;  ///< the slender-rod value, for comparison (0: none)
};

struct Measured {
  std::vector<double> hz;  ///< the lowest components found, ascending
  bool converged = false;
  std::string run;
};

/// The lowest `count` frequencies of `signal` (per output) of a run, divided by `harmonic`.
Measured lowest(const result::DynamicResult& r, const std::vector<double>& signal, int count,
                double harmonic) {
  Measured m{{}, r.converged, dynamics::run_text(r)};
  if (!r.converged || r.t.size() < 30) return m;
  std::vector<double> y = signal;
  double mean = 0.0;
  for (double v : y) mean += v / static_cast<double>(y.size());
  for (double& v : y) v -= mean;
  const auto components = signal_components(y, r.t[2] - r.t[1], 2 * count + 5);
  for (int i = 0; i < count && i < static_cast<int>(components.size()); ++i)
    m.hz.push_back(components[i].frequency_hz / harmonic);
  return m;
}

/// Runs the three free vibrations with a scheme at N and measures their frequencies.
std::vector<double> measure(const std::string& scheme, int nodes, std::string& runs, bool& ok) {
  const double L = Table21::L;
  struct Motion {
    scene::Scene scene;
    double t_end;
    int count;
    int signal;  // 0: tip x, 1: tip z, 2: kinetic energy
  };
  const Motion motions[] = {
      {released("bending", vector_text(1e-3 * Table21::EI / (L * L), 0, 0), vector_text(0, 0, 0)),
       0.5, 3, 0},
      {released("torsion", vector_text(0, 0, 0), vector_text(0, 0, 1e-4 * Table21::GJ / L)), 0.1,
       1, 2},
      {released("axial", vector_text(0, 0, 1e-4 * Table21::EA), vector_text(0, 0, 0)), 0.1, 1, 1},
  };
  std::vector<double> hz;
  ok = true;
  for (const auto& m : motions) {
    const double dt = scheme == "ida" ? 1e-4 : dynamics::auto_dt(m.scene, scheme, nodes);
    const auto r = dynamics::simulate(m.scene, scheme, nodes, dt, m.t_end,
                                      scene::Initial::static_equilibrium, 1200);
    std::vector<double> signal;
    for (std::size_t k = 0; k < r.t.size(); ++k)
      signal.push_back(m.signal == 2 ? r.energy.kinetic[k]
                                     : r.tip_position[k][m.signal == 0 ? 0 : 2]);
    const auto found = lowest(r, signal, m.count, m.signal == 2 ? 2.0 : 1.0);
    runs += m.scene.name + ": " + found.run + "; ";
    ok = ok && found.converged && static_cast<int>(found.hz.size()) == m.count;
    for (int i = 0; i < m.count; ++i)
      hz.push_back(i < static_cast<int>(found.hz.size()) ? found.hz[i] : NAN);
  }
  return hz;
}

std::vector<Mode> modes() {
  const double L = Table21::L;
  const auto bending = reference::timoshenko_cantilever_frequencies(
      {L, Table21::EI, Table21::GA, Table21::rhoA, Table21::rho * Table21::I}, 3);
  const double eb = std::sqrt(Table21::EI / (Table21::rhoA * std::pow(L, 4))) / (2 * Table21::pi);
  // The circle's torsion constant is its polar moment: c = sqrt(G Jt / (rho J)) = sqrt(G / rho).
  const double torsion_speed = std::sqrt(Table21::G / Table21::rho);
  const double axial_speed = std::sqrt(Table21::E / Table21::rho);
  return {
      {"bending 1", bending[0], 1.8751040687 * 1.8751040687 * eb},
      {"bending 2", bending[1], 4.6940911330 * 4.6940911330 * eb},
      {"bending 3", bending[2], 7.8547574382 * 7.8547574382 * eb},
      {"torsion 1", reference::clamped_free_wave_frequency(L, torsion_speed, 1), 0.0},
      {"axial 1", reference::clamped_free_wave_frequency(L, axial_speed, 1), 0.0},
  };
}

}  // namespace

std::vector<Check> free_vibration_frequencies(const ValidationContext& context) {
  DataSet data{.name = "literature_frequencies",
               .description = "natural frequencies of the Table 2.1 cantilever from free "
                              "vibration against the Timoshenko beam and the wave equations",
               .columns = {"series", "mode", "scheme", "N", "measured_hz", "reference_hz",
                           "euler_bernoulli_hz", "relative_error"}};
  struct Run {
    const char* scheme;
    int nodes;
  };
  const std::vector<Run> runs = context.full
                                    ? std::vector<Run>{{"variational", 10}, {"variational", 20},
                                                       {"variational", 40}, {"variational", 80},
                                                       {"ida", 40}}
                                    : std::vector<Run>{{"variational", 40}};
  const auto reference = modes();
  std::vector<Check> checks;
  for (const auto& [scheme, nodes] : runs) {
    std::string text;
    bool ok = false;
    const auto hz = measure(scheme, nodes, text, ok);
    for (std::size_t i = 0; i < reference.size(); ++i) {
      const auto& mode = reference[i];
      const double error = std::abs(hz[i] / mode.reference_hz - 1.0);
      data.add_row({mode.name + " (" + scheme + ")", mode.name, scheme, nodes, hz[i],
                    mode.reference_hz, mode.euler_bernoulli_hz, error});
      if (nodes < 40) continue;  // the coarse meshes show the convergence only
      Check c = relative_check(
          "free vibration, " + mode.name + ": " + scheme + " N = " + std::to_string(nodes) +
              " frequency [Hz]",
          hz[i], mode.reference_hz, 1e-3,
          mode.euler_bernoulli_hz > 0 ? "Timoshenko beam (Huang 1961), shear and rotary inertia"
                                      : "wave equation, clamped-free");
      c.passed = c.passed && ok;
      c.detail = text;
      checks.push_back(c);
    }
  }
  data.figures.push_back(
      {.name = "literature_frequencies",
       .kind = "loglog",
       .x = "N",
       .y = {"relative_error"},
       .series = "series",
       .title = "Natural frequencies from free vibration",
       .xlabel = "nodes N",
       .ylabel = "|f / f_reference - 1|",
       .caption = "Relative error of the first three bending, the first torsional and the first "
                  "axial frequencies of the Table 2.1 cantilever (L / D = 10), read by the matrix "
                  "pencil from variational's free vibration (dt auto; --full: N = 10 .. 80, and "
                  "ida at N = 40), against the Timoshenko beam (shear and rotary inertia; "
                  "Euler-Bernoulli is 0.6, 4 and 9 % higher) and the wave equations. Dashed: "
                  "slope -2.",
       .reference_slopes = {-2.0},
       .style = "lines+markers"});
  context.emit(std::move(data));
  return checks;
}

}  // namespace rodlab::validation
