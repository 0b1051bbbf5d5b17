#include "result_output.hpp"

#include <iostream>

#include "rodlab/io/result_writer.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/io/text_table.hpp"

#include "exit_status.hpp"

namespace rodlab::cli {
namespace {

std::string status(bool converged, const std::string& reason) {
  return converged ? std::string("converged") : "NOT converged: " + reason;
}

template <class Result>
int deliver_impl(const Result& result, const std::optional<std::filesystem::path>& out,
                 const std::optional<std::filesystem::path>& vtk) {
  if (out) io::write_result(*out, result);
  std::cout << summarize(result);
  if (out) std::cout << "result written to " << out->string() << '\n';
  if (vtk) std::cout << "ParaView files in " << vtk->string() << '\n';
  return result.converged ? kSolved : kNotConverged;
}

}  // namespace

std::string summarize(const result::StaticResult& r) {
  io::TextTable t;
  t.add_row({"scene", r.scene});
  t.add_row({"scheme", r.scheme + ", " + std::to_string(r.nodes) + " nodes"});
  t.add_row({"status", status(r.converged, r.reason)});
  t.add_row({"iterations", std::to_string(r.iterations)});
  t.add_row({"residual norm", io::format_number(r.residual_norm)});
  if (!r.centerline.empty())
    t.add_row({"tip position", io::format_vector(r.centerline.back().pose.translation()) + " m"});
  t.add_row({"base moment", io::format_vector(r.base_wrench.head<3>()) + " N m"});
  t.add_row({"base force", io::format_vector(r.base_wrench.tail<3>()) + " N"});
  t.add_row({"max |det R - 1|", io::format_number(r.max_det_deviation)});
  t.add_row({"wall time", io::format_number(r.wall_time_s) + " s"});
  return t.render();
}

std::string summarize(const result::DynamicResult& r) {
  io::TextTable t;
  t.add_row({"scene", r.scene});
  t.add_row({"scheme", r.scheme + ", " + std::to_string(r.nodes) + " nodes, dt " +
                           io::format_number(r.dt) + " s, " + std::to_string(r.steps) + " steps"});
  t.add_row({"status", status(r.converged, r.reason)});
  if (!r.t.empty()) t.add_row({"final time", io::format_number(r.t.back()) + " s"});
  if (!r.tip_position.empty())
    t.add_row({"final tip position", io::format_vector(r.tip_position.back()) + " m"});
  if (!r.energy.total.empty())
    t.add_row({"energy balance drift",
               io::format_number(r.energy.total.back() - r.energy.total.front()) + " J"});
  t.add_row({"wall time", io::format_number(r.wall_time_s) + " s (real-time ratio " +
                              io::format_number(r.real_time_ratio) + ")"});
  return t.render();
}

int deliver(const result::StaticResult& result, const std::optional<std::filesystem::path>& out,
            const std::optional<std::filesystem::path>& vtk) {
  return deliver_impl(result, out, vtk);
}

int deliver(const result::DynamicResult& result, const std::optional<std::filesystem::path>& out,
            const std::optional<std::filesystem::path>& vtk) {
  return deliver_impl(result, out, vtk);
}

}  // namespace rodlab::cli
