#include "rodlab/io/result_writer.hpp"

#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "rodlab/check.hpp"
#include "rodlab/io/atomic_file.hpp"

namespace rodlab::io {
namespace {

using Json = nlohmann::ordered_json;  // keeps the spec's key order

Json vector_json(const Eigen::Ref<const Eigen::VectorXd>& v) {
  Json out = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

Json rotation_json(const lie::Matrix3& R) {
  Json rows = Json::array();
  for (int i = 0; i < 3; ++i) rows.push_back(vector_json(R.row(i).transpose()));
  return rows;
}

Json centerline_json(const std::vector<result::CenterlineSample>& samples) {
  Json out = Json::array();
  for (const auto& sample : samples) {
    out.push_back(Json{{"s", sample.s},
                       {"position", vector_json(sample.pose.translation())},
                       {"rotation", rotation_json(sample.pose.rotation_matrix())},
                       {"twist", vector_json(sample.twist)}});
  }
  return out;
}

Json status_json(bool converged, const std::string& reason) {
  Json out{{"converged", converged}};
  if (!converged) out["reason"] = reason.empty() ? std::string("unknown") : reason;
  return out;
}

std::string dump(const Json& json) {
  // error_handler::replace: a stray invalid UTF-8 byte in a scene name must not lose a result.
  return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

/// %.17g: max_digits10 for double, so every value reads back exactly.
void append_number(std::string& out, double value) {
  static_assert(std::numeric_limits<double>::max_digits10 == 17);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  out += buffer;
}

void append_row(std::string& out, const std::vector<double>& row) {
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i > 0) out += ',';
    append_number(out, row[i]);
  }
  out += '\n';
}

/// Throws unless a series has one value per row: "dynamic result: energy.strain has 2 values
/// for 3 output times".
void check_length(std::size_t size, const char* result, const char* name, std::size_t rows,
                  const char* per) {
  RODLAB_THROW_UNLESS(size == rows, "{} result: {} has {} values for {} {}", result, name, size,
                      rows, per);
}

const std::vector<double>& checked_series(const std::vector<double>& series, const char* name,
                                          std::size_t expected) {
  check_length(series.size(), "dynamic", name, expected, "output times");
  return series;
}

template <class Result>
void write_result_impl(const std::filesystem::path& path, const Result& result) {
  const std::string text =
      result_format(path) == ResultFormat::json ? to_json(result) : to_csv(result);
  write_file_atomically(path, text);
}

}  // namespace

ResultFormat result_format(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return ResultFormat::json;
  if (ext == ".csv") return ResultFormat::csv;
  throw std::invalid_argument(
      rodlab::format("result file {}: extension must be .json or .csv (got '{}')", path.string(),
                     ext));
}

std::string to_json(const result::StaticResult& r) {
  Json json{{"schema", kStaticResultSchema},
            {"scene", r.scene},
            {"scheme", r.scheme},
            {"nodes", r.nodes}};
  json.update(status_json(r.converged, r.reason));
  json["iterations"] = r.iterations;
  json["residual_norm"] = r.residual_norm;
  json["wall_time_s"] = r.wall_time_s;
  if (r.centerline.empty()) {
    json["tip"] = nullptr;
  } else {
    const lie::SE3& tip = r.centerline.back().pose;
    json["tip"] = Json{{"position", vector_json(tip.translation())},
                       {"rotation", rotation_json(tip.rotation_matrix())}};
  }
  json["base_wrench"] = Json{{"moment", vector_json(r.base_wrench.head<3>())},
                             {"force", vector_json(r.base_wrench.tail<3>())}};
  json["centerline"] = centerline_json(r.centerline);
  json["diagnostics"] = Json{{"max_det_deviation", r.max_det_deviation},
                             {"max_orthogonality_error", r.max_orthogonality_error}};
  return dump(json);
}

std::string to_json(const result::DynamicResult& r) {
  Json json{{"schema", kDynamicResultSchema},
            {"scene", r.scene},
            {"scheme", r.scheme},
            {"nodes", r.nodes},
            {"dt", r.dt},
            {"steps", r.steps}};
  json.update(status_json(r.converged, r.reason));
  json["wall_time_s"] = r.wall_time_s;
  json["real_time_ratio"] = r.real_time_ratio;
  Json tip = Json::array();
  for (const auto& p : r.tip_position) tip.push_back(vector_json(p));
  const auto& e = r.energy;
  json["series"] = Json{{"t", r.t},
                        {"tip_position", tip},
                        {"energy", Json{{"kinetic", e.kinetic},
                                        {"strain", e.strain},
                                        {"gravity", e.gravity},
                                        {"dissipated", e.dissipated},
                                        {"work_in", e.work_in},
                                        {"total", e.total}}},
                        {"max_det_deviation", r.max_det_deviation}};
  json["final"] = Json{{"centerline", centerline_json(r.final_centerline)}};
  return dump(json);
}

std::string to_csv(const result::StaticResult& r) {
  std::string out = "s,x,y,z,R00,R01,R02,R10,R11,R12,R20,R21,R22,xi0,xi1,xi2,xi3,xi4,xi5\n";
  std::vector<double> row;
  for (const auto& sample : r.centerline) {
    row.clear();
    row.push_back(sample.s);
    const lie::Vector3& p = sample.pose.translation();
    row.insert(row.end(), p.data(), p.data() + 3);
    const lie::Matrix3 R = sample.pose.rotation_matrix();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) row.push_back(R(i, j));
    row.insert(row.end(), sample.twist.data(), sample.twist.data() + 6);
    append_row(out, row);
  }
  return out;
}

std::string to_csv(const result::DynamicResult& r) {
  const std::size_t n = r.t.size();
  check_length(r.tip_position.size(), "dynamic", "tip_position", n, "output times");
  const auto& e = r.energy;
  const std::vector<const std::vector<double>*> columns{
      &checked_series(e.kinetic, "energy.kinetic", n),
      &checked_series(e.strain, "energy.strain", n),
      &checked_series(e.gravity, "energy.gravity", n),
      &checked_series(e.dissipated, "energy.dissipated", n),
      &checked_series(e.work_in, "energy.work_in", n),
      &checked_series(e.total, "energy.total", n),
      &checked_series(r.max_det_deviation, "max_det_deviation", n)};
  std::string out =
      "t,tip_x,tip_y,tip_z,kinetic,strain,gravity,dissipated,work_in,total,max_det_deviation\n";
  std::vector<double> row;
  for (std::size_t k = 0; k < n; ++k) {
    row.assign({r.t[k], r.tip_position[k].x(), r.tip_position[k].y(), r.tip_position[k].z()});
    for (const auto* column : columns) row.push_back((*column)[k]);
    append_row(out, row);
  }
  return out;
}

void write_result(const std::filesystem::path& path, const result::StaticResult& result) {
  write_result_impl(path, result);
}

void write_result(const std::filesystem::path& path, const result::DynamicResult& result) {
  write_result_impl(path, result);
}

}  // namespace rodlab::io

namespace rodlab::io {

std::string to_json(const result::WorkspaceResult& r) {
  Json tips = Json::array();
  for (const auto& sample : r.samples) {
    tips.push_back(Json{{"inputs", sample.inputs},
                        {"tip", vector_json(sample.tip)},
                        {"omega", sample.coordinates.omega},
                        {"phi", sample.coordinates.phi},
                        {"epsilon", sample.coordinates.epsilon},
                        {"converged", sample.converged}});
  }
  const Json json{{"schema", kWorkspaceResultSchema},
                  {"scene", r.scene},
                  {"scheme", r.scheme},
                  {"nodes", r.nodes},
                  {"length", r.length},
                  {"seed", r.seed},
                  {"samples", r.samples.size()},
                  {"failed", r.failed},
                  {"wall_time_s", r.wall_time_s},
                  {"bounds", Json{{"omega_bound", r.bounds.omega_bound},
                                  {"eps_low", r.bounds.eps_low},
                                  {"eps_high", r.bounds.eps_high}}},
                  {"tips", tips}};
  return dump(json);
}

std::string to_csv(const result::WorkspaceResult& r) {
  std::string out;
  const std::size_t inputs = r.samples.empty() ? 0 : r.samples.front().inputs.size();
  for (std::size_t k = 0; k < inputs; ++k) out += "input" + std::to_string(k) + ",";
  out += "tip_x,tip_y,tip_z,omega,phi,epsilon,converged\n";
  std::vector<double> row;
  for (const auto& sample : r.samples) {
    row = sample.inputs;
    row.insert(row.end(), sample.tip.data(), sample.tip.data() + 3);
    row.push_back(sample.coordinates.omega);
    row.push_back(sample.coordinates.phi);
    row.push_back(sample.coordinates.epsilon);
    row.push_back(sample.converged ? 1.0 : 0.0);
    append_row(out, row);
  }
  return out;
}

void write_result(const std::filesystem::path& path, const result::WorkspaceResult& result) {
  write_result_impl(path, result);
}

}  // namespace rodlab::io

namespace rodlab::io {
namespace {

const char* target_source_name(result::TargetSource source) {
  switch (source) {
    case result::TargetSource::scene:
      return "scene";
    case result::TargetSource::trajectory:
      return "trajectory";
    case result::TargetSource::static_workspace:
      return "static-workspace";
    case result::TargetSource::dynamic_workspace:
      return "dynamic-workspace";
    case result::TargetSource::policy:
      return "policy";
  }
  return "unknown";
}

Json text_or_null(const std::optional<std::string>& text) {
  return text ? Json(*text) : Json(nullptr);
}

Json points_json(const std::vector<lie::Vector3>& points) {
  Json out = Json::array();
  for (const auto& p : points) out.push_back(vector_json(p));
  return out;
}

/// One value per control step in every series, inputs of one size, episodes that exist.
void check_control_series(const result::ControlResult& r) {
  const auto& s = r.series;
  const std::size_t n = s.t.size();
  const auto check = [&](std::size_t size, const char* name) {
    check_length(size, "control", name, n, "control steps");
  };
  check(s.u.size(), "series.u");
  check(s.tip.size(), "series.tip");
  check(s.target.size(), "series.target");
  check(s.error.size(), "series.error");
  check(s.solve_time_s.size(), "series.solve_time_s");
  check(s.iterations.size(), "series.iterations");
  check(s.episode.size(), "series.episode");
  for (std::size_t k = 0; k < n; ++k) {
    RODLAB_THROW_UNLESS(s.u[k].size() == s.u.front().size(),
                        "control result: series.u[{}] has {} inputs, series.u[0] {}", k,
                        s.u[k].size(), s.u.front().size());
    RODLAB_THROW_UNLESS(s.episode[k] >= 0 && static_cast<std::size_t>(s.episode[k]) <
                                                 r.episodes.size(),
                        "control result: series.episode[{}] = {} is not one of the {} episodes",
                        k, s.episode[k], r.episodes.size());
  }
}

Json episodes_json(const std::vector<result::ControlEpisode>& episodes) {
  Json out = Json::array();
  for (const auto& e : episodes) {
    out.push_back(Json{{"target", vector_json(e.target)},
                       {"success", e.success},
                       {"steps", e.steps},
                       {"final_error", e.final_error},
                       {"min_error", e.min_error},
                       {"mean_error", e.mean_error},
                       {"reason", text_or_null(e.reason)}});
  }
  return out;
}

Json control_series_json(const result::ControlSeries& s) {
  Json u = Json::array();
  for (const auto& inputs : s.u) u.push_back(vector_json(inputs));
  return Json{{"t", s.t},
              {"u", u},
              {"tip", points_json(s.tip)},
              {"target", points_json(s.target)},
              {"error", s.error},
              {"solve_time_s", s.solve_time_s},
              {"iterations", s.iterations},
              {"episode", s.episode}};
}

}  // namespace

std::string to_json(const result::ControlResult& r) {
  check_control_series(r);
  Json json{{"schema", kControlResultSchema},
            {"scene", r.scene},
            {"controller", r.controller},
            {"task", r.task},
            {"scheme", r.scheme},
            {"nodes", r.nodes},
            {"dt_control", r.dt_control},
            {"horizon", r.horizon},
            {"converged", r.converged}};
  json["reason"] = (r.reason || r.converged) ? text_or_null(r.reason) : Json("unknown");
  json["episodes"] = episodes_json(r.episodes);
  json["series"] = control_series_json(r.series);
  const auto& m = r.summary;
  json["summary"] = Json{{"success_rate", m.success_rate},
                         {"mean_error_pct_L", m.mean_error_pct_L},
                         {"real_time_ratio_mean", m.real_time_ratio_mean},
                         {"real_time_ratio_max", m.real_time_ratio_max},
                         {"wall_time_s", m.wall_time_s},
                         {"samples", m.samples ? Json(*m.samples) : Json(nullptr)}};
  json["seed"] = r.seed;
  json["targets"] = Json{{"drawn_from", target_source_name(r.targets.drawn_from)},
                         {"points", points_json(r.targets.points)}};
  json["model_scheme"] = text_or_null(r.model_scheme);
  return dump(json);
}

std::string to_csv(const result::ControlResult& r) {
  check_control_series(r);
  const auto& s = r.series;
  const Eigen::Index inputs = s.u.empty() ? 0 : s.u.front().size();
  std::string out = "t,";
  for (Eigen::Index i = 0; i < inputs; ++i) out += rodlab::format("u_{},", i);
  out += "tip_x,tip_y,tip_z,target_x,target_y,target_z,error,solve_time_s,iterations,episode\n";
  std::vector<double> row;
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    row.assign({s.t[k]});
    row.insert(row.end(), s.u[k].data(), s.u[k].data() + inputs);
    row.insert(row.end(), s.tip[k].data(), s.tip[k].data() + 3);
    row.insert(row.end(), s.target[k].data(), s.target[k].data() + 3);
    row.insert(row.end(), {s.error[k], s.solve_time_s[k], static_cast<double>(s.iterations[k]),
                           static_cast<double>(s.episode[k])});
    append_row(out, row);
  }
  return out;
}

void write_result(const std::filesystem::path& path, const result::ControlResult& result) {
  write_result_impl(path, result);
}

}  // namespace rodlab::io
