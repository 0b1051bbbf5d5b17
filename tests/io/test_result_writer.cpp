#define BOOST_TEST_MODULE result_writer
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rodlab/io/atomic_file.hpp"
#include "rodlab/io/result_writer.hpp"

// Reference: the layout of interface spec section 4 and "Control and learning". Numbers must
// read back bit for bit, so every comparison of a number below is exact (BOOST_TEST with ==, no
// tolerance).

namespace fs = std::filesystem;
using rodlab::lie::SE3;
using rodlab::lie::SO3;
using rodlab::lie::Vector3;
using rodlab::lie::Vector6;
using rodlab::result::CenterlineSample;
using rodlab::result::ControlResult;
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

/// Two episodes (3 and 2 control steps) of a four-cable robot, every number with many digits.
ControlResult control_result() {
  ControlResult r;
  r.scene = "control-cable";
  r.controller = "nlsq-mpc";
  r.task = "reach";
  r.scheme = "implicit-midpoint";
  r.nodes = 20;
  r.dt_control = 0.05 / 3.0;
  r.horizon = 10;
  r.converged = true;
  r.seed = 42;
  r.targets.drawn_from = rodlab::result::TargetSource::dynamic_workspace;
  r.targets.points = {Vector3(0.02 / 3.0, -1.0 / 700.0, 0.099), Vector3(-1e-3 / 7.0, 0.01, 0.0985)};
  for (std::size_t e = 0; e < 2; ++e) {
    rodlab::result::ControlEpisode episode;
    episode.target = r.targets.points[e];
    episode.success = e == 0;
    episode.steps = e == 0 ? 3 : 2;
    episode.final_error = 1e-3 / (3.0 + e);
    episode.min_error = 1e-4 / (7.0 + e);
    episode.mean_error = 2e-3 / (9.0 + e);
    r.episodes.push_back(episode);
  }
  r.episodes[1].reason = "target unreachable: inputs at their limits";
  auto& s = r.series;
  for (int k = 0; k < 5; ++k) {
    const int episode = k < 3 ? 0 : 1;
    const double t = ((k < 3 ? k : k - 3) + 1) * r.dt_control;
    s.t.push_back(t);
    s.u.push_back((Eigen::VectorXd(4) << 0.5 / 3.0 * k, 0.0, 1e-17 * k, 0.5).finished());
    s.tip.emplace_back(t / 7.0, -t / 11.0, 0.1 - t * 1e-3);
    s.target.push_back(r.targets.points[static_cast<std::size_t>(episode)]);
    s.error.push_back((s.tip.back() - s.target.back()).norm());
    s.solve_time_s.push_back(1e-3 * std::sqrt(k + 2.0));
    s.iterations.push_back(3 * k + 1);
    s.episode.push_back(episode);
  }
  r.summary.success_rate = 0.5;
  r.summary.mean_error_pct_L = 100.0 / 3.0;
  r.summary.real_time_ratio_mean = 0.4 / 3.0;
  r.summary.real_time_ratio_max = 0.7 / 3.0;
  r.summary.wall_time_s = 3.1 / 7.0;
  return r;
}

std::vector<double> csv_row(const std::string& line) {
  std::vector<double> values;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) values.push_back(std::stod(cell));
  return values;
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

// ---- control (rodlab.control-result/1)

BOOST_AUTO_TEST_CASE(control_json_has_every_key_of_the_spec) {
  const ControlResult r = control_result();
  const std::string text = rodlab::io::to_json(r);
  const Json j = Json::parse(text);
  // the spec's keys in its order, then the extensions seed, targets and model_scheme
  const std::vector<std::string> expected_keys{
      "schema",  "scene",     "controller", "task",     "scheme", "nodes",   "dt_control",
      "horizon", "converged", "reason",     "episodes", "series", "summary", "seed",
      "targets", "model_scheme"};
  BOOST_TEST(keys(text) == expected_keys, boost::test_tools::per_element());
  BOOST_TEST(j["schema"] == "rodlab.control-result/1");
  BOOST_TEST(j["scene"] == "control-cable");
  BOOST_TEST(j["controller"] == "nlsq-mpc");
  BOOST_TEST(j["task"] == "reach");
  BOOST_TEST(j["scheme"] == "implicit-midpoint");
  BOOST_TEST(j["nodes"].is_number_integer());
  BOOST_TEST(j["nodes"].get<int>() == 20);
  BOOST_TEST(j["dt_control"].get<double>() == r.dt_control);
  BOOST_TEST(j["horizon"].is_number_integer());
  BOOST_TEST(j["horizon"].get<int>() == 10);
  BOOST_TEST(j["converged"].get<bool>());
  BOOST_TEST(j["reason"].is_null());  // present, and null when fine
  BOOST_TEST(j["model_scheme"].is_null());  // the plant's scheme predicted
  ControlResult split = r;
  split.model_scheme = "implicit-midpoint";
  BOOST_TEST(Json::parse(rodlab::io::to_json(split))["model_scheme"] == "implicit-midpoint");

  BOOST_REQUIRE_EQUAL(j["episodes"].size(), 2u);
  const std::vector<std::string> episode_keys{"target",    "success",    "steps", "final_error",
                                              "min_error", "mean_error", "reason"};
  BOOST_TEST(keys(nlohmann::ordered_json::parse(text)["episodes"][0].dump()) == episode_keys,
             boost::test_tools::per_element());
  for (std::size_t e = 0; e < 2; ++e) {
    const Json& je = j["episodes"][e];
    const auto& re = r.episodes[e];
    check_vector(je["target"], re.target);
    BOOST_TEST(je["success"].get<bool>() == re.success);
    BOOST_TEST(je["steps"].is_number_integer());
    BOOST_TEST(je["steps"].get<int>() == re.steps);
    BOOST_TEST(je["final_error"].get<double>() == re.final_error);
    BOOST_TEST(je["min_error"].get<double>() == re.min_error);
    BOOST_TEST(je["mean_error"].get<double>() == re.mean_error);
  }
  BOOST_TEST(j["episodes"][0]["reason"].is_null());
  BOOST_TEST(j["episodes"][1]["reason"] == "target unreachable: inputs at their limits");

  const Json& s = j["series"];
  const std::vector<std::string> series_keys{"t",     "u",            "tip",        "target",
                                             "error", "solve_time_s", "iterations", "episode"};
  BOOST_TEST(keys(nlohmann::ordered_json::parse(text)["series"].dump()) == series_keys,
             boost::test_tools::per_element());
  BOOST_TEST(s["t"].get<std::vector<double>>() == r.series.t, boost::test_tools::per_element());
  BOOST_REQUIRE_EQUAL(s["u"].size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    check_vector(s["u"][k], r.series.u[k]);
    check_vector(s["tip"][k], r.series.tip[k]);
    check_vector(s["target"][k], r.series.target[k]);
  }
  BOOST_TEST(s["error"].get<std::vector<double>>() == r.series.error,
             boost::test_tools::per_element());
  BOOST_TEST(s["solve_time_s"].get<std::vector<double>>() == r.series.solve_time_s,
             boost::test_tools::per_element());
  BOOST_TEST(s["iterations"].get<std::vector<int>>() == r.series.iterations,
             boost::test_tools::per_element());
  BOOST_TEST(s["episode"].get<std::vector<int>>() == r.series.episode,
             boost::test_tools::per_element());

  const std::vector<std::string> summary_keys{"success_rate",         "mean_error_pct_L",
                                              "real_time_ratio_mean", "real_time_ratio_max",
                                              "wall_time_s",          "samples"};
  BOOST_TEST(keys(nlohmann::ordered_json::parse(text)["summary"].dump()) == summary_keys,
             boost::test_tools::per_element());
  const Json& m = j["summary"];
  BOOST_TEST(m["success_rate"].get<double>() == 0.5);
  BOOST_TEST(m["mean_error_pct_L"].get<double>() == r.summary.mean_error_pct_L);
  BOOST_TEST(m["real_time_ratio_mean"].get<double>() == r.summary.real_time_ratio_mean);
  BOOST_TEST(m["real_time_ratio_max"].get<double>() == r.summary.real_time_ratio_max);
  BOOST_TEST(m["wall_time_s"].get<double>() == r.summary.wall_time_s);
  BOOST_TEST(m["samples"].is_null());  // not a learned policy

  BOOST_TEST(j["seed"].get<unsigned>() == 42u);
  BOOST_TEST(j["targets"]["drawn_from"] == "dynamic-workspace");
  BOOST_REQUIRE_EQUAL(j["targets"]["points"].size(), 2u);
  for (std::size_t e = 0; e < 2; ++e) check_vector(j["targets"]["points"][e], r.targets.points[e]);
}

BOOST_AUTO_TEST_CASE(control_json_reports_reasons_samples_and_target_sources) {
  ControlResult r = control_result();
  r.converged = false;
  r.reason = "nlsq-mpc: Ceres failed at step 4";
  r.summary.samples = 123456789012L;
  r.targets.drawn_from = rodlab::result::TargetSource::static_workspace;
  Json j = Json::parse(rodlab::io::to_json(r));
  BOOST_TEST(!j["converged"].get<bool>());
  BOOST_TEST(j["reason"] == "nlsq-mpc: Ceres failed at step 4");
  BOOST_TEST(j["summary"]["samples"].get<long>() == 123456789012L);
  BOOST_TEST(j["targets"]["drawn_from"] == "static-workspace");

  r.reason.reset();  // a failure without a reason still says so
  j = Json::parse(rodlab::io::to_json(r));
  BOOST_TEST(j["reason"] == "unknown");

  r.converged = true;  // solved, but a target was unreachable: exit 1 with a reason
  r.reason = "1 of 2 targets unreachable";
  r.targets.drawn_from = rodlab::result::TargetSource::trajectory;
  j = Json::parse(rodlab::io::to_json(r));
  BOOST_TEST(j["converged"].get<bool>());
  BOOST_TEST(j["reason"] == "1 of 2 targets unreachable");
  BOOST_TEST(j["targets"]["drawn_from"] == "trajectory");
  r.targets.drawn_from = rodlab::result::TargetSource::scene;
  BOOST_TEST(Json::parse(rodlab::io::to_json(r))["targets"]["drawn_from"] == "scene");
}

BOOST_AUTO_TEST_CASE(control_csv_has_one_row_per_control_step) {
  const ControlResult r = control_result();
  const auto rows = lines(rodlab::io::to_csv(r));
  BOOST_REQUIRE_EQUAL(rows.size(), 6u);
  BOOST_TEST(rows[0] ==
             "t,u_0,u_1,u_2,u_3,tip_x,tip_y,tip_z,target_x,target_y,target_z,error,solve_time_s,"
             "iterations,episode");
  for (std::size_t k = 0; k < 5; ++k) {
    const auto& s = r.series;
    std::vector<double> expected{s.t[k]};
    expected.insert(expected.end(), s.u[k].data(), s.u[k].data() + 4);
    expected.insert(expected.end(), s.tip[k].data(), s.tip[k].data() + 3);
    expected.insert(expected.end(), s.target[k].data(), s.target[k].data() + 3);
    expected.insert(expected.end(), {s.error[k], s.solve_time_s[k], double(s.iterations[k]),
                                     double(s.episode[k])});
    BOOST_TEST(csv_row(rows[k + 1]) == expected, boost::test_tools::per_element());
  }
  // no steps: the header without inputs
  ControlResult empty = r;
  empty.series = {};
  BOOST_TEST(rodlab::io::to_csv(empty) ==
             "t,tip_x,tip_y,tip_z,target_x,target_y,target_z,error,solve_time_s,iterations,"
             "episode\n");
}

BOOST_AUTO_TEST_CASE(control_writers_reject_inconsistent_series) {
  const auto rejected = [](const ControlResult& r) {
    BOOST_CHECK_THROW(rodlab::io::to_json(r), std::invalid_argument);
    BOOST_CHECK_THROW(rodlab::io::to_csv(r), std::invalid_argument);
  };
  ControlResult r = control_result();
  r.series.iterations.pop_back();
  rejected(r);
  r = control_result();
  r.series.tip.pop_back();
  rejected(r);
  r = control_result();
  r.series.u[3] = Eigen::VectorXd::Zero(3);  // three inputs where the others have four
  rejected(r);
  r = control_result();
  r.series.episode[4] = 2;  // only episodes 0 and 1 exist
  rejected(r);
  r.series.episode[4] = -1;
  rejected(r);
}

BOOST_AUTO_TEST_CASE(control_result_files_round_trip_and_are_written_atomically) {
  TempDir dir;
  ControlResult r = control_result();
  rodlab::io::write_result(dir.path / "c.json", r);
  rodlab::io::write_result(dir.path / "c.csv", r);
  BOOST_TEST(read(dir.path / "c.json") == rodlab::io::to_json(r));
  BOOST_TEST(read(dir.path / "c.csv") == rodlab::io::to_csv(r));
  const Json j = Json::parse(read(dir.path / "c.json"));
  BOOST_TEST(j["schema"] == "rodlab.control-result/1");
  BOOST_TEST(j["series"]["error"].get<std::vector<double>>() == r.series.error,
             boost::test_tools::per_element());
  BOOST_TEST(lines(read(dir.path / "c.csv")).size() == 6u);

  // overwriting replaces the whole file; an inconsistent result writes nothing and keeps it
  r.series = {};
  r.episodes.clear();
  rodlab::io::write_result(dir.path / "c.json", r);
  BOOST_TEST(read(dir.path / "c.json") == rodlab::io::to_json(r));
  const std::string kept = read(dir.path / "c.json");
  r.series.t.push_back(0.05);
  BOOST_CHECK_THROW(rodlab::io::write_result(dir.path / "c.json", r), std::invalid_argument);
  BOOST_TEST(read(dir.path / "c.json") == kept);
  // no temporary files left: only the two results
  BOOST_TEST(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 2);

  // a missing directory: WriteError naming the path, nothing created
  BOOST_CHECK_THROW(rodlab::io::write_result(dir.path / "missing" / "c.json", control_result()),
                    rodlab::io::WriteError);
  BOOST_CHECK_THROW(rodlab::io::write_result(dir.path / "c.yaml", control_result()),
                    std::invalid_argument);
  BOOST_TEST(!fs::exists(dir.path / "missing"));
  BOOST_TEST(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 2);
}
