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

const std::vector<double>& checked_series(const std::vector<double>& series, const char* name,
                                          std::size_t expected) {
  RODLAB_THROW_UNLESS(series.size() == expected,
                      "dynamic result: {} has {} values for {} output times", name, series.size(),
                      expected);
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
  RODLAB_THROW_UNLESS(r.tip_position.size() == n,
                      "dynamic result: tip_position has {} values for {} output times",
                      r.tip_position.size(), n);
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
