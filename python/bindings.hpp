#pragma once
// What the files of the Python module share (docs/python.md): the scene as Python holds it, a
// centreline's and the results' arrays, the command line's options from keyword arguments, and
// each file's bind function. PYBIND11_MODULE (rodlab_module.cpp) calls them in turn.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/result/static_result.hpp"

#include "common_options.hpp"

namespace rodlab::python {

namespace py = pybind11;

using RowMatrix3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrix6 = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

/// A scene as loaded: its source (a file, or YAML text and a name) and the overrides set on it.
struct PyScene {
  std::optional<std::string> path;
  std::string text, name;
  std::vector<io::Override> overrides;
  scene::Scene scene;

  /// Loads and checks the source with the overrides (throws io::SceneError).
  void reload();
};

/// A centreline as arrays, base first: s (N), positions (N x 3), rotations (N x 3 x 3, the
/// columns are the frame d1, d2, d3), twists (N x 6, [kappa; nu]).
struct Centerline {
  Eigen::VectorXd s;
  RowMatrix3 positions;
  std::vector<double> rotations;
  RowMatrix6 twists;

  explicit Centerline(const std::vector<result::CenterlineSample>& c);
};

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
  explicit PyDynamicResult(result::DynamicResult in);
};

/// The command line's options from keyword arguments (None: not given); raises ValueError for
/// a scheme that does not fit `problem`.
cli::SolveOptions solve_options(const PyScene& s, solvers::Problem problem, const char* command,
                                const std::optional<std::string>& scheme,
                                std::optional<int> nodes, std::optional<double> tol);

/// The module's parts, one per file.
void bind_scene(py::module_& m);     ///< scene_bindings.cpp: Scene, SceneError
void bind_results(py::module_& m);   ///< result_bindings.cpp: Centerline, the result classes
void bind_solve(py::module_& m);     ///< solve_bindings.cpp: solve_*, study, schemes
void bind_stepping(py::module_& m);  ///< stepping_bindings.cpp: Simulation, Plant

}  // namespace rodlab::python
