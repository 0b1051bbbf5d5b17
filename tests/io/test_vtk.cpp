// The VTK XML writer (rodlab/io/vtk.hpp): what it refuses and how a point cloud and a polyline
// are laid out (the files themselves are read back by VTK in test_vtk_files.py).
#define BOOST_TEST_MODULE io_vtk
#include <boost/test/unit_test.hpp>

#include <stdexcept>

#include "rodlab/io/vtk.hpp"

namespace io = rodlab::io;

namespace {
io::VtkPolyData two_points() {
  io::VtkPolyData d;
  d.points = {{0, 0, 0}, {0, 0, 0.5}};
  return d;
}
bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}
}  // namespace

BOOST_AUTO_TEST_CASE(refuses_inconsistent_data) {
  io::VtkPolyData d = two_points();
  d.add_scalars("s", {0.0});  // one value for two points
  BOOST_CHECK_THROW(io::vtp_text(d), std::invalid_argument);
  d = two_points();
  d.lines = {{0, 2}};  // no point 2
  BOOST_CHECK_THROW(io::vtp_text(d), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(cloud_polyline_time_and_collection) {
  io::VtkPolyData cloud = two_points();
  const std::string c = io::vtp_text(cloud);
  BOOST_TEST(contains(c, "NumberOfPoints=\"2\" NumberOfVerts=\"2\" NumberOfLines=\"0\""));
  BOOST_TEST(!contains(c, "TimeValue"));
  io::VtkPolyData rod = two_points();
  rod.lines = {{0, 1}};
  rod.time = 0.25;
  rod.add_vectors("d3", {{0, 0, 1}, {0, 0, 1}});
  const std::string r = io::vtp_text(rod);
  BOOST_TEST(contains(r, "NumberOfVerts=\"0\" NumberOfLines=\"1\""));
  BOOST_TEST(contains(r, "Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">\n          0.25"));
  BOOST_TEST(contains(r, "Name=\"d3\" NumberOfComponents=\"3\""));
  BOOST_TEST(r.find("<FieldData>") < r.find("<Piece"));  // VTK's place for it
  const std::string p = io::pvd_text({{0.5, 1, "a&b.vtp"}});
  BOOST_TEST(contains(p, "<DataSet timestep=\"0.5\" group=\"\" part=\"1\" file=\"a&amp;b.vtp\"/>"));
}
