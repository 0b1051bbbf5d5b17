// The Python module `rodlab` (issue #16; docs/python.md): scenes, statics, dynamics and a
// stepping plant from Python, built from the same libraries as the command line. A solve takes
// its options the way `rodlab static` / `rodlab dynamic` do (apps/rodlab/common_options.hpp:
// the keyword arguments are the command line's options, resolved over the scene by the same
// code), so the same scene and options give the command line's result to the last bit.
//
// Arrays: a result's arrays are NumPy views of memory the result object owns (no copy); each
// view keeps its result alive (NumPy's base object), so a view may outlive the name bound to
// the result.
#include "bindings.hpp"

PYBIND11_MODULE(rodlab, m) {
  namespace rp = rodlab::python;
  m.doc() = "rodlab: Cosserat and Kirchhoff rods (docs/python.md)";
  rp::bind_scene(m);
  rp::bind_results(m);
  rp::bind_solve(m);
  rp::bind_stepping(m);
}
