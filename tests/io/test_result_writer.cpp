#define BOOST_TEST_MODULE result_writer
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rodlab/io/result_writer.hpp"

// Reference: the layout of interface spec section 4. Numbers must read back bit for bit,
// so every comparison of a number below is exact (BOOST_TEST with ==, no tolerance).

namespace fs = std::filesystem;
using rodlab::lie::SE3;
using rodlab::lie::SO3;
using rodlab::lie::Vector3;
using rodlab::lie::Vector6;
using rodlab::result::CenterlineSample;
using rodlab::result::DynamicResult;
using rodlab::result::StaticResult;
using Json = nlohmann::json;

namespace {

// Values with many significant digits, so that any loss of precision shows.
CenterlineSample sample(int k) {
  CenterlineSample c;
  c.s = 0.1 * k / 3.0;
  c.pose = SE3(SO3::exp(Vector3(0.1 / 3.0 * k, -0.2 / 7.0, 1.0 / 9.0)),
               Vector3(1.0 / 3.0 * k, 2.0 / 7.0, std::sqrt(2.0) * k));
  c.twist << 1.0 / 3.0, -2.0 / 3.0, 1e-300, std::acos(-1.0), 0.0, 1.0 + k * 1e-16;
  return c;
}

StaticResult static_result(bool converged) {
  StaticResult r;
  r.scene = "cantilever-gravity";
  r.scheme = "chebyshev";
  r.nodes = 3;
  r.converged = converged;
  if (!converged) r.reason = "Newton stalled after 50 iterations";
  r.iterations = 6;
  r.residual_norm = 3.1e-13;
  r.wall_time_s = 0.0004;
  for (int k = 0; k < 3; ++k) r.centerline.push_back(sample(k));
  r.base_wrench << 1.0 / 3.0, 2.0 / 3.0, -1.0 / 7.0, 0.1, 0.2, 0.3;
  r.max_det_deviation = 2.220446049250313e-16;
  r.max_orthogonality_error = 4.440892098500626e-16;
  return r;
}

DynamicResult dynamic_result(std::size_t outputs) {
  DynamicResult r;
  r.scene = "swing";
  r.scheme = "variational";
  r.nodes = 20;
  r.dt = 1e-5 / 3.0;
  r.steps = 200000;
  r.converged = true;
  r.wall_time_s = 1.9;
  r.real_time_ratio = 0.95;
  for (std::size_t k = 0; k < outputs; ++k) {
    const double t = k / 3.0;
    r.t.push_back(t);
    r.tip_position.emplace_back(t, -t / 7.0, 0.1 + t * 1e-17);
    r.energy.kinetic.push_back(1.0 * t / 11.0);
    r.energy.strain.push_back(2.0 * t / 11.0);
    r.energy.gravity.push_back(-3.0 * t / 11.0);
    r.energy.dissipated.push_back(4.0 * t / 11.0);
    r.energy.work_in.push_back(5.0 * t / 11.0);
    r.energy.total.push_back(6.0 * t / 11.0);
    r.max_det_deviation.push_back(t * 1e-16);
  }
  for (int k = 0; k < 3; ++k) r.final_centerline.push_back(sample(k));
  return r;
}

void check_vector(const Json& j, const Eigen::Ref<const Eigen::VectorXd>& v) {
  BOOST_REQUIRE(j.is_array());
  BOOST_REQUIRE_EQUAL(j.size(), static_cast<std::size_t>(v.size()));
  for (Eigen::Index i = 0; i < v.size(); ++i) BOOST_TEST(j[i].get<double>() == v[i]);
}

void check_rotation(const Json& j, const rodlab::lie::Matrix3& R) {
  BOOST_REQUIRE(j.is_array());
  BOOST_REQUIRE_EQUAL(j.size(), 3u);
  for (int i = 0; i < 3; ++i) check_vector(j[i], R.row(i).transpose());
}

void check_centerline(const Json& j, const std::vector<CenterlineSample>& samples) {
  BOOST_REQUIRE(j.is_array());
  BOOST_REQUIRE_EQUAL(j.size(), samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    BOOST_TEST(j[k].size() == 4u);
    BOOST_TEST(j[k]["s"].get<double>() == samples[k].s);
    check_vector(j[k]["position"], samples[k].pose.translation());
    check_rotation(j[k]["rotation"], samples[k].pose.rotation_matrix());
    check_vector(j[k]["twist"], samples[k].twist);
  }
}

/// The keys of an object in file order (nlohmann::json sorts them; ordered_json does not).
std::vector<std::string> keys(const std::string& text) {
  const auto object = nlohmann::ordered_json::parse(text);
  std::vector<std::string> out;
  for (const auto& item : object.items()) out.push_back(item.key());
  return out;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A fresh empty directory under the system temp directory, removed at the end of a test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("rodlab-result-writer-" + std::to_string(::getpid()) + "-" +
                                        std::to_string(counter()++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  static int& counter() {
    static int n = 0;
    return n;
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(static_json_has_every_key_of_the_spec) {
  const StaticResult r = static_result(true);
  const std::string text = rodlab::io::to_json(r);
  const Json j = Json::parse(text);
  // Spec order, and no "reason" when converged.
  const std::vector<std::string> expected_keys{
      "schema",        "scene",       "scheme", "nodes",       "converged",  "iterations",
      "residual_norm", "wall_time_s", "tip",    "base_wrench", "centerline", "diagnostics"};
  BOOST_TEST(keys(text) == expected_keys, boost::test_tools::per_element());

  BOOST_TEST(j["schema"] == "rodlab.static-result/1");
  BOOST_TEST(j["scene"] == "cantilever-gravity");
  BOOST_TEST(j["scheme"] == "chebyshev");
  BOOST_TEST(j["nodes"].is_number_integer());
  BOOST_TEST(j["nodes"].get<int>() == 3);
  BOOST_TEST(j["converged"].is_boolean());
  BOOST_TEST(j["converged"].get<bool>());
  BOOST_TEST(j["iterations"].is_number_integer());
  BOOST_TEST(j["iterations"].get<int>() == 6);
  BOOST_TEST(j["residual_norm"].get<double>() == 3.1e-13);
  BOOST_TEST(j["wall_time_s"].get<double>() == 0.0004);

  check_vector(j["tip"]["position"], r.centerline.back().pose.translation());
  check_rotation(j["tip"]["rotation"], r.centerline.back().pose.rotation_matrix());
  check_vector(j["base_wrench"]["moment"], r.base_wrench.head<3>());
  check_vector(j["base_wrench"]["force"], r.base_wrench.tail<3>());
  check_centerline(j["centerline"], r.centerline);
  BOOST_TEST(j["diagnostics"]["max_det_deviation"].get<double>() == r.max_det_deviation);
  BOOST_TEST(j["diagnostics"]["max_orthogonality_error"].get<double>() ==
             r.max_orthogonality_error);
}

BOOST_AUTO_TEST_CASE(static_json_reports_the_reason_when_not_converged) {
  const std::string text = rodlab::io::to_json(static_result(false));
  const Json j = Json::parse(text);
  BOOST_TEST(j["converged"].get<bool>() == false);
  BOOST_REQUIRE(j.contains("reason"));
  BOOST_TEST(j["reason"] == "Newton stalled after 50 iterations");
  const auto k = keys(text);
  BOOST_TEST(k[4] == "converged");
  BOOST_TEST(k[5] == "reason");
}

BOOST_AUTO_TEST_CASE(non_finite_numbers_become_null) {
  StaticResult r = static_result(false);
  r.residual_norm = std::nan("");
  const Json j = Json::parse(rodlab::io::to_json(r));
  BOOST_TEST(j["residual_norm"].is_null());
}

BOOST_AUTO_TEST_CASE(dynamic_json_has_every_key_of_the_spec) {
  const DynamicResult r = dynamic_result(4);
  const std::string text = rodlab::io::to_json(r);
  const Json j = Json::parse(text);
  const std::vector<std::string> expected_keys{
      "schema",    "scene",       "scheme",          "nodes",  "dt",   "steps",
      "converged", "wall_time_s", "real_time_ratio", "series", "final"};
  BOOST_TEST(keys(text) == expected_keys, boost::test_tools::per_element());
  BOOST_TEST(j["schema"] == "rodlab.dynamic-result/1");
  BOOST_TEST(j["scene"] == "swing");
  BOOST_TEST(j["scheme"] == "variational");
  BOOST_TEST(j["nodes"].get<int>() == 20);
  BOOST_TEST(j["dt"].get<double>() == r.dt);
  BOOST_TEST(j["steps"].is_number_integer());
  BOOST_TEST(j["steps"].get<long>() == 200000);
  BOOST_TEST(j["converged"].get<bool>());
  BOOST_TEST(!j.contains("reason"));
  BOOST_TEST(j["wall_time_s"].get<double>() == 1.9);
  BOOST_TEST(j["real_time_ratio"].get<double>() == 0.95);

  const Json& s = j["series"];
  const std::vector<std::string> series_keys{"t", "tip_position", "energy", "max_det_deviation"};
  BOOST_TEST(keys(nlohmann::ordered_json::parse(text)["series"].dump()) == series_keys,
             boost::test_tools::per_element());
  BOOST_TEST(s["t"].get<std::vector<double>>() == r.t, boost::test_tools::per_element());
  BOOST_REQUIRE_EQUAL(s["tip_position"].size(), r.tip_position.size());
  for (std::size_t k = 0; k < r.tip_position.size(); ++k)
    check_vector(s["tip_position"][k], r.tip_position[k]);
  const std::vector<std::string> energy_keys{"kinetic",    "strain",  "gravity",
                                             "dissipated", "work_in", "total"};
  BOOST_TEST(keys(nlohmann::ordered_json::parse(text)["series"]["energy"].dump()) == energy_keys,
             boost::test_tools::per_element());
  const auto& e = r.energy;
  BOOST_TEST(s["energy"]["kinetic"].get<std::vector<double>>() == e.kinetic,
             boost::test_tools::per_element());
  BOOST_TEST(s["energy"]["strain"].get<std::vector<double>>() == e.strain,
             boost::test_tools::per_element());
  BOOST_TEST(s["energy"]["gravity"].get<std::vector<double>>() == e.gravity,
             boost::test_tools::per_element());
  BOOST_TEST(s["energy"]["dissipated"].get<std::vector<double>>() == e.dissipated,
             boost::test_tools::per_element());
  BOOST_TEST(s["energy"]["work_in"].get<std::vector<double>>() == e.work_in,
             boost::test_tools::per_element());
  BOOST_TEST(s["energy"]["total"].get<std::vector<double>>() == e.total,
             boost::test_tools::per_element());
  BOOST_TEST(s["max_det_deviation"].get<std::vector<double>>() == r.max_det_deviation,
             boost::test_tools::per_element());
  check_centerline(j["final"]["centerline"], r.final_centerline);
}

BOOST_AUTO_TEST_CASE(static_csv_has_one_row_per_node) {
  const StaticResult r = static_result(true);
  const auto rows = lines(rodlab::io::to_csv(r));
  BOOST_REQUIRE_EQUAL(rows.size(), 1 + r.centerline.size());
  BOOST_TEST(rows[0] == "s,x,y,z,R00,R01,R02,R10,R11,R12,R20,R21,R22,xi0,xi1,xi2,xi3,xi4,xi5");
  // Last row, read back exactly.
  std::vector<double> values;
  std::istringstream in(rows.back());
  for (std::string cell; std::getline(in, cell, ',');) values.push_back(std::stod(cell));
  BOOST_REQUIRE_EQUAL(values.size(), 19u);
  const auto& c = r.centerline.back();
  BOOST_TEST(values[0] == c.s);
  for (int i = 0; i < 3; ++i) BOOST_TEST(values[1 + i] == c.pose.translation()[i]);
  const auto R = c.pose.rotation_matrix();
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) BOOST_TEST(values[4 + 3 * i + k] == R(i, k));
  for (int i = 0; i < 6; ++i) BOOST_TEST(values[13 + i] == c.twist[i]);
}

BOOST_AUTO_TEST_CASE(dynamic_csv_has_one_row_per_output_time) {
  const DynamicResult r = dynamic_result(5);
  const auto rows = lines(rodlab::io::to_csv(r));
  BOOST_REQUIRE_EQUAL(rows.size(), 6u);
  BOOST_TEST(
      rows[0] ==
      "t,tip_x,tip_y,tip_z,kinetic,strain,gravity,dissipated,work_in,total,max_det_deviation");
  std::vector<double> values;
  std::istringstream in(rows[2]);
  for (std::string cell; std::getline(in, cell, ',');) values.push_back(std::stod(cell));
  const std::vector<double> expected{r.t[1],
                                     r.tip_position[1].x(),
                                     r.tip_position[1].y(),
                                     r.tip_position[1].z(),
                                     r.energy.kinetic[1],
                                     r.energy.strain[1],
                                     r.energy.gravity[1],
                                     r.energy.dissipated[1],
                                     r.energy.work_in[1],
                                     r.energy.total[1],
                                     r.max_det_deviation[1]};
  BOOST_TEST(values == expected, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(dynamic_csv_rejects_a_short_series) {
  DynamicResult r = dynamic_result(3);
  r.energy.strain.pop_back();
  BOOST_CHECK_THROW(rodlab::io::to_csv(r), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(extension_chooses_the_format) {
  using rodlab::io::ResultFormat;
  BOOST_TEST((rodlab::io::result_format("a/b.json") == ResultFormat::json));
  BOOST_TEST((rodlab::io::result_format("b.csv") == ResultFormat::csv));
  BOOST_CHECK_THROW(rodlab::io::result_format("b.txt"), std::invalid_argument);
  BOOST_CHECK_THROW(rodlab::io::result_format("b"), std::invalid_argument);
  BOOST_CHECK_THROW(rodlab::io::result_format("b.JSON"), std::invalid_argument);

  TempDir dir;
  const StaticResult s = static_result(true);
  rodlab::io::write_result(dir.path / "r.json", s);
  rodlab::io::write_result(dir.path / "r.csv", s);
  BOOST_TEST(read(dir.path / "r.json") == rodlab::io::to_json(s));
  BOOST_TEST(read(dir.path / "r.csv") == rodlab::io::to_csv(s));

  const DynamicResult d = dynamic_result(2);
  rodlab::io::write_result(dir.path / "d.json", d);
  rodlab::io::write_result(dir.path / "d.csv", d);
  BOOST_TEST(read(dir.path / "d.json") == rodlab::io::to_json(d));
  BOOST_TEST(read(dir.path / "d.csv") == rodlab::io::to_csv(d));
}

BOOST_AUTO_TEST_CASE(another_extension_throws_and_writes_nothing) {
  TempDir dir;
  BOOST_CHECK_THROW(rodlab::io::write_result(dir.path / "r.txt", static_result(true)),
                    std::invalid_argument);
  BOOST_CHECK_THROW(rodlab::io::write_result(dir.path / "r.yaml", dynamic_result(1)),
                    std::invalid_argument);
  BOOST_TEST(fs::is_empty(dir.path));
}
