// rodlab.Centerline, rodlab.StaticResult, rodlab.DynamicResult: a result's arrays as NumPy views
// of memory the result object owns, each holding its result alive (docs/python.md).
#include "bindings.hpp"

namespace rodlab::python {
namespace {

py::array rotations_view(const Centerline& c, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(c.s.size());
  return py::array_t<double>({n, py::ssize_t{3}, py::ssize_t{3}},
                             {py::ssize_t{72}, py::ssize_t{24}, py::ssize_t{8}},
                             c.rotations.data(), owner);
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
/// What every result has: scheme, nodes, converged, reason, wall_time_s.
template <class R>
void common_properties(py::class_<R>& c) {
  c.def_property_readonly("scheme", [](const R& r) { return r.r.scheme; })
      .def_property_readonly("nodes", [](const R& r) { return r.r.nodes; })
      .def_property_readonly("converged", [](const R& r) { return r.r.converged; })
      .def_property_readonly("reason", [](const R& r) { return r.r.reason; })
      .def_property_readonly("wall_time_s", [](const R& r) { return r.r.wall_time_s; });
}

}  // namespace

Centerline::Centerline(const std::vector<result::CenterlineSample>& c)
    : s(c.size()), positions(c.size(), 3), rotations(9 * c.size()), twists(c.size(), 6) {
  for (std::size_t j = 0; j < c.size(); ++j) {
    s[j] = c[j].s;
    positions.row(j) = c[j].pose.translation().transpose();
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rotations.data() + 9 * j) =
        c[j].pose.rotation_matrix();
    twists.row(j) = c[j].twist.transpose();
  }
}

PyDynamicResult::PyDynamicResult(result::DynamicResult in)
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

void bind_results(py::module_& m) {
  py::class_<Centerline>(m, "Centerline")
      .def_property_readonly("s", view(&Centerline::s))
      .def_property_readonly("positions", view(&Centerline::positions))
      .def_property_readonly("rotations",
                             [](py::object self) { return rotations_view(self.cast<const Centerline&>(), self); })
      .def_property_readonly("twists", view(&Centerline::twists));
  py::class_<PyStaticResult> statics(m, "StaticResult");
  common_properties(statics);
  statics
      .def_property_readonly("iterations", [](const PyStaticResult& r) { return r.r.iterations; })
      .def_property_readonly("residual_norm",
                             [](const PyStaticResult& r) { return r.r.residual_norm; })
      .def_property_readonly("base_wrench",
                             [](const PyStaticResult& r) { return Eigen::VectorXd(r.r.base_wrench); })
      .def_property_readonly("centerline", [](py::object self) {
        return py::cast(&self.cast<PyStaticResult&>().centerline,
                        py::return_value_policy::reference_internal, self);
      });
  py::class_<PyDynamicResult> dynamics(m, "DynamicResult");
  common_properties(dynamics);
  dynamics
      .def_property_readonly("dt", [](const PyDynamicResult& r) { return r.r.dt; })
      .def_property_readonly("steps", [](const PyDynamicResult& r) { return r.r.steps; })
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
}  // namespace rodlab::python
