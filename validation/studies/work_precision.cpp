#include "studies/work_precision.hpp"

#include <cmath>

namespace rodlab::validation::study {

std::vector<bool> pareto_front(const Sweep& sweep) {
  const auto& rows = sweep.rows;
  auto eligible = [](const SweepRow& r) {
    return r.role == "study" && r.run.converged && std::isfinite(r.error);
  };
  std::vector<bool> front(rows.size(), false);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!eligible(rows[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < rows.size() && !dominated; ++j) {
      if (j == i || !eligible(rows[j])) continue;
      const double ei = rows[i].error, ej = rows[j].error;
      const double ti = rows[i].run.wall_time_s, tj = rows[j].run.wall_time_s;
      dominated = ej <= ei && tj <= ti && (ej < ei || tj < ti);
    }
    front[i] = !dominated;
  }
  return front;
}

std::string work_precision_csv(const Sweep& sweep, const std::vector<bool>& pareto) {
  std::string out =
      "scheme,role,nodes,dt,error,max_error,wall_time_s,wall_time_min_s,repeats,converged,"
      "pareto,reason,grid\n";
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) {
    const auto& r = sweep.rows[i];
    const bool dyn = r.spec.problem == solvers::Problem::dynamics;
    out += csv_text(r.spec.scheme) + ',' + r.role + ',' + std::to_string(r.spec.nodes) + ',' +
           (dyn ? csv_number(r.run.dt) : "") + ',' + csv_number(r.error) + ',' +
           (dyn ? csv_number(r.max_error) : "") + ',' + csv_number(r.run.wall_time_s) + ',' +
           csv_number(r.run.wall_time_min_s) + ',' + std::to_string(r.run.repeats) + ',' +
           (r.run.converged ? "true" : "false") + ',' + (pareto[i] ? "true" : "false") + ',' +
           csv_text(r.note.empty() ? r.run.reason : r.note) + ',' + r.grid + '\n';
  }
  return out;
}

Json work_precision_json(const Sweep& sweep, const std::vector<bool>& pareto,
                         const Settings& settings) {
  Json j = sweep_json(sweep, settings, "work-precision");
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) j["rows"][i]["pareto"] = bool(pareto[i]);
  j["timing"] = {{"statistic", "median of the repeats of the solver's own wall time"},
                 {"repeats", settings.repeats},
                 {"slow_run_s", kSlowRunSeconds}};
  return j;
}

Recommendation recommend(const Json& rows, double tol, std::optional<double> budget_ms,
                         ErrorMeasure measure) {
  Recommendation rec;
  const char* field = measure == ErrorMeasure::over_the_run ? "max_error" : "error";
  for (const auto& row : rows) {
    if (row.value("role", "") != "study" || !row.value("converged", false) ||
        !row.contains(field) || !row[field].is_number())
      continue;
    Candidate c;
    c.scheme = row["scheme"].get<std::string>();
    if (row.contains("grid") && row["grid"].is_string()) c.grid = row["grid"].get<std::string>();
    c.nodes = row["nodes"].get<int>();
    if (row["dt"].is_number()) c.dt = row["dt"].get<double>();
    c.error = row[field].get<double>();
    c.wall_time_s = row["wall_time_s"].get<double>();
    c.repeats = row.value("repeats", 1);
    ++rec.candidates;
    if (!rec.most_accurate || c.error < rec.most_accurate->error) rec.most_accurate = c;
    if (c.error > tol) continue;
    if (!rec.fastest_meeting_tol || c.wall_time_s < rec.fastest_meeting_tol->wall_time_s)
      rec.fastest_meeting_tol = c;
    if (budget_ms && c.wall_time_s * 1e3 > *budget_ms) continue;
    if (!rec.best || c.wall_time_s < rec.best->wall_time_s) rec.best = c;
  }
  return rec;
}

}  // namespace rodlab::validation::study
