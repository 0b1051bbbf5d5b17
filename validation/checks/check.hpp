#pragma once
// The checks of `rodlab validate`. A check compares one measured number with a reference
// whose origin is stated (closed form, other scheme, SUNDIALS reference, literature), within
// a stated tolerance. Checks come in families; each family is one function registered in
// check_families() (validation_families.cpp), so a later issue adds its checks by adding one
// function and one line there.
//
// A family may also emit data sets (ValidationContext::emit): the numbers behind its checks as a
// table (DIR/data/NAME.csv), each with the figures drawn from it (DIR/figures/FIGURE.svg, by
// validation/make_figures.py from the CSV and the figure spec in report.json).
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rodlab::validation {

struct Check {
  std::string family;              ///< the family that made it, e.g. "scenes"
  std::string name;                ///< e.g. "cantilever-gravity: K[0] = E pi D^4/64"
  double measured = 0.0;           ///< what the code computed
  std::optional<double> expected;  ///< the reference value, when it is a number
  double tolerance = 0.0;          ///< on relative_error(), or as the check says
  std::string reference;           ///< where the reference comes from
  bool passed = false;
  std::string detail;  ///< why it failed, or extra context
  /// A headline check: the report's summary topic it belongs to (report/summary.hpp: order,
  /// reference, energy, structure, recommend); empty for the details only.
  std::string topic;

  /// |measured - expected| / |expected| (absolute when expected is 0); 0 without expected.
  double relative_error() const;
};

/// Passes when |measured - expected| <= tolerance |expected|.
Check relative_check(std::string name, double measured, double expected, double tolerance,
                     std::string reference);
/// Passes when measured <= bound (finite); expected = bound, tolerance 0, the bound named in
/// the reference.
Check upper_bound_check(std::string name, double measured, double bound, std::string reference);
/// Passes when lo <= measured <= hi; expected = (lo + hi) / 2, tolerance = the half-width
/// relative to it.
Check range_check(std::string name, double measured, double lo, double hi, std::string reference);
/// The check as a headline of the report's summary topic (Check::topic).
Check with_topic(Check check, std::string topic);
/// A yes/no check (measured 1 or 0, expected 1).
Check boolean_check(std::string name, bool ok, std::string reference, std::string detail = {});

/// One cell of a data set: a number (written with 17 significant digits) or a label.
struct Cell {
  std::string text;
  bool numeric = true;
  Cell(double v);  // NOLINT(google-explicit-constructor): rows are written as {1.0, "rk4", 3}
  Cell(int v);     // NOLINT(google-explicit-constructor)
  Cell(long v);    // NOLINT(google-explicit-constructor)
  Cell(std::string s) : text(std::move(s)), numeric(false) {}  // NOLINT
  Cell(const char* s) : text(s), numeric(false) {}             // NOLINT
};

/// How validation/make_figures.py draws one figure from a data set.
struct FigureSpec {
  std::string name;   ///< file stem: figures/NAME.svg (unique over the report)
  /// line | loglog | semilogy | semilogx | shape (equal axes) | map | pareto (work-precision:
  /// log-log markers per series, the rows whose `pareto` column is 1 joined as the front, those
  /// whose `recommended` column is 1 starred)
  std::string kind;
  std::string x;      ///< column on the horizontal axis
  /// One curve per column (map: y[0] the colour, y[1] the vertical axis unless series is set)
  std::vector<std::string> y;
  std::string series;  ///< optional: one curve (map: one row) per distinct value of this column
  std::string title, xlabel, ylabel;
  std::string caption;                  ///< what the reader sees, under the figure
  std::vector<double> reference_slopes; ///< loglog: dashed lines of these slopes
  std::string style = "lines";          ///< lines | markers | lines+markers
  bool absolute = false;                ///< plot |y| (log axes of signed errors)
  std::string select;                   ///< only the rows whose series value starts with this
};

/// A table of numbers behind some checks, written to DIR/data/NAME.csv.
struct DataSet {
  std::string name;  ///< file stem: data/NAME.csv (unique over the report)
  std::string family;
  std::string description;
  std::vector<std::string> columns;
  std::vector<std::vector<Cell>> rows;
  std::vector<FigureSpec> figures;
  /// Optional Markdown shown in the report as is (report.md; index.html as preformatted text),
  /// e.g. the Table 4.1 reproduction of the control study.
  std::string table;

  /// Appends a row (throws std::logic_error if its width is not columns.size()).
  void add_row(std::vector<Cell> row);
  /// The CSV text: a header line, then one line per row (labels quoted when needed).
  std::string to_csv() const;
};

/// Where families put their data sets: run_checks sets the family name on each.
struct DataSink {
  std::vector<DataSet> data_sets;
  std::string current_family;
};

struct ValidationContext {
  std::filesystem::path scenes_dir;  ///< the example scenes (*.yaml)
  bool full = false;                 ///< --full: also the slow checks
  DataSink* sink = nullptr;          ///< where emit() goes; nullptr drops the data
  /// The rodlab executable the extremes family runs as child processes; empty: this program.
  std::filesystem::path program;
  /// Called before each family runs (its name, families done, families to run) and once when
  /// all have run (no name): progress.
  std::function<void(std::string_view family, int done, int total)> on_family;

  /// Records a data set (and its figures) for the report.
  void emit(DataSet data) const;
};

struct CheckFamily {
  std::string_view name;
  std::string_view description;
  std::vector<Check> (*run)(const ValidationContext&);
};

/// Every family, in report order.
std::span<const CheckFamily> check_families();

/// Runs the families whose names are in `only` (every family when empty); a family that throws
/// yields one failed check saying so. Data sets go to context.sink.
std::vector<Check> run_checks(const ValidationContext& context,
                              std::span<const std::string> only = {});

/// The scene files of a directory (*.yaml, sorted by name).
std::vector<std::filesystem::path> scene_files(const std::filesystem::path& dir);

}  // namespace rodlab::validation

namespace rodlab::validation {

// The families (one file each), registered in validation_families.cpp.

/// validation_scene_checks.cpp: every example scene loads, and its derived quantities
/// (section properties, K, M, V, wave speeds, the explicit step (3.44), the Kirchhoff error
/// estimate) equal their closed forms.
std::vector<Check> scene_checks(const ValidationContext& context);

/// validation_statics_checks.cpp: observed orders on the gravity cantilever, both ends fixed,
/// closed forms (full circle, straight cable), reference agreement, structure drift.
std::vector<Check> statics_checks(const ValidationContext& context);

/// validation_dynamics_checks.cpp: bending frequency against its closed form, energy without
/// and with damping, det drift, the stability limit, the static limit, agreement between
/// schemes and with the IDA reference.
std::vector<Check> dynamics_checks(const ValidationContext& context);

/// literature_checks.cpp: the classic rod benchmarks of issue #18 against closed forms, an
/// rk8pd planar reference and published tables (docs/validation.md "literature").
std::vector<Check> literature_checks(const ValidationContext& context);

/// validation_study_checks.cpp: the studies (study_*.hpp) on example scenes: work-precision
/// sweeps (statics, dynamics) with their Pareto fronts and `study recommend` answers checked
/// against an independent reference (timings are reported, never gated), the stability map of
/// the explicit scheme and the implicit schemes' step scans.
std::vector<Check> study_checks(const ValidationContext& context);

/// control_checks.cpp: the thesis' Table 4.1 by `rodlab study control` (--quick: NLSQ-MPC on
/// implicit-midpoint at dt_c = 0.05 s, H = 1 and 5, dynamic reach of 3 targets and the middle
/// circle; --full: the whole table), checked against Table 4.1's NLSQ Implicit columns.
std::vector<Check> control_checks(const ValidationContext& context);

/// learning_checks.cpp: the DDPG and GPS columns of Table 4.1 by `rodlab study learning`
/// (--quick: reach-one, one seed; --full: three tasks, five seeds, learning curves), checked
/// against issue #15's bounds.
std::vector<Check> learning_checks(const ValidationContext& context);

/// extremes_checks.cpp: every scheme at the extremes of E, N and dt, run as child processes:
/// exit 0 only with finite results, otherwise exit 1 with a reason or exit 2 up front; no crash,
/// no hang past the budget; the map of what runs.
std::vector<Check> extremes_checks(const ValidationContext& context);

}  // namespace rodlab::validation
