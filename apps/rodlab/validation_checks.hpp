#pragma once
// The checks of `rodlab validate`. A check compares one measured number with a reference
// whose origin is stated (closed form, other scheme, SUNDIALS reference, literature), within
// a stated tolerance. Checks come in families; each family is one function registered in
// check_families() (validation_checks.cpp), so a later issue adds its checks by adding one
// function and one line there.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rodlab::cli {

struct Check {
  std::string family;              ///< the family that made it, e.g. "scenes"
  std::string name;                ///< e.g. "cantilever-gravity: K[0] = E pi D^4/64"
  double measured = 0.0;           ///< what the code computed
  std::optional<double> expected;  ///< the reference value, when it is a number
  double tolerance = 0.0;          ///< on relative_error(), or as the check says
  std::string reference;           ///< where the reference comes from
  bool passed = false;
  std::string detail;  ///< why it failed, or extra context

  /// |measured - expected| / |expected| (absolute when expected is 0); 0 without expected.
  double relative_error() const;
};

/// Passes when |measured - expected| <= tolerance |expected|.
Check relative_check(std::string name, double measured, double expected, double tolerance,
                     std::string reference);
/// A yes/no check (measured 1 or 0, expected 1).
Check boolean_check(std::string name, bool ok, std::string reference, std::string detail = {});

struct ValidationContext {
  std::filesystem::path scenes_dir;  ///< the example scenes (*.yaml)
  bool full = false;                 ///< --full: also the slow checks
};

struct CheckFamily {
  std::string_view name;
  std::string_view description;
  std::vector<Check> (*run)(const ValidationContext&);
};

/// Every family, in report order.
std::span<const CheckFamily> check_families();

/// Runs every family; a family that throws yields one failed check saying so.
std::vector<Check> run_checks(const ValidationContext& context);

/// The scene files of a directory (*.yaml, sorted by name).
std::vector<std::filesystem::path> scene_files(const std::filesystem::path& dir);

}  // namespace rodlab::cli

namespace rodlab::cli {

// The families (one file each), registered in validation_checks.cpp.

/// validation_scene_checks.cpp: every example scene loads, and its derived quantities
/// (section properties, K, M, V, wave speeds, the explicit step (3.44), the Kirchhoff error
/// estimate) equal their closed forms.
std::vector<Check> scene_checks(const ValidationContext& context);

/// validation_statics_checks.cpp: observed orders on the gravity cantilever, both ends fixed,
/// closed forms (full circle, straight cable), reference agreement, structure drift.
std::vector<Check> statics_checks(const ValidationContext& context);

}  // namespace rodlab::cli
