#pragma once
// Result files (interface spec section 4 and "Control and learning"): JSON with the schema
// strings rodlab.static-result/1, rodlab.dynamic-result/1 and rodlab.control-result/1, or CSV; the format follows the file
// extension, and files are written atomically (rodlab/io/atomic_file.hpp).
//
// JSON: keys in the spec's order; "reason" appears only when converged is false; rotations
// are 3 rows of 3; numbers are written so that they read back bit for bit (shortest
// round-trip form, at most max_digits10 = 17 significant digits); a NaN or an infinity
// (e.g. the residual of a diverged run) is written as null.
//
// CSV (comma separated, one header line, numbers with max_digits10 digits):
//   static : one row per centreline node:  s,x,y,z,R00,R01,...,R22,xi0,...,xi5
//            (R row-major, xi = [omega; nu])
//   dynamic: one row per output time:      t,tip_x,tip_y,tip_z,kinetic,strain,gravity,
//                                          dissipated,work_in,total,max_det_deviation
//   control: one row per control step:     t,u_0,...,u_{m-1},tip_x,tip_y,tip_z,target_x,
//                                          target_y,target_z,error,solve_time_s,iterations,episode
#include <filesystem>
#include <string>

#include "rodlab/result/control_result.hpp"
#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/result/static_result.hpp"
#include "rodlab/result/workspace_result.hpp"

namespace rodlab::io {

inline constexpr const char* kStaticResultSchema = "rodlab.static-result/1";
inline constexpr const char* kDynamicResultSchema = "rodlab.dynamic-result/1";
inline constexpr const char* kWorkspaceResultSchema = "rodlab.workspace-result/1";
inline constexpr const char* kControlResultSchema = "rodlab.control-result/1";

enum class ResultFormat { json, csv };

/// The format for a result path by its extension (.json or .csv, lower case);
/// throws std::invalid_argument naming the path for anything else.
ResultFormat result_format(const std::filesystem::path& path);

/// JSON text of a result (indented by 2, trailing newline).
std::string to_json(const result::StaticResult& result);
std::string to_json(const result::DynamicResult& result);
/// Workspace: {"schema", "scene", "scheme", "nodes", "length", "seed", "samples": N, "failed",
/// "wall_time_s", "bounds": {"omega_bound", "eps_low", "eps_high"},
/// "tips": [{"inputs": [...], "tip": [x, y, z], "omega", "phi", "epsilon", "converged"}, ...]}
std::string to_json(const result::WorkspaceResult& result);
/// Control (docs/control.md "Result file"): the spec's keys in its order, "reason" always
/// (null when fine; also in each episode), then the extensions "seed" and
/// "targets": {"drawn_from": scene | trajectory | static-workspace | dynamic-workspace,
/// "points": [[x, y, z], ...]}; series adds "episode". Throws std::invalid_argument when the
/// series do not have one value per control step, inputs differ in size, or an episode index
/// is out of range.
std::string to_json(const result::ControlResult& result);

/// CSV text of a result. The dynamic writer throws std::invalid_argument when a series does
/// not have one value per output time.
std::string to_csv(const result::StaticResult& result);
std::string to_csv(const result::DynamicResult& result);
/// Workspace CSV: one row per sample: input0..inputK-1,tip_x,tip_y,tip_z,omega,phi,epsilon,converged
std::string to_csv(const result::WorkspaceResult& result);
/// Control CSV: one row per control step (above); the same checks as its JSON.
std::string to_csv(const result::ControlResult& result);

/// Writes the result to `path`, JSON or CSV by extension, atomically. Throws
/// std::invalid_argument for another extension (nothing is written) and std::system_error
/// when the file cannot be written (nothing is left behind).
void write_result(const std::filesystem::path& path, const result::StaticResult& result);
void write_result(const std::filesystem::path& path, const result::DynamicResult& result);
void write_result(const std::filesystem::path& path, const result::WorkspaceResult& result);
void write_result(const std::filesystem::path& path, const result::ControlResult& result);

}  // namespace rodlab::io
