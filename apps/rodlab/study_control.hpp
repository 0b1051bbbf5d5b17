#pragma once
// `rodlab study control SCENE`: the thesis' Table 4.1 (validation/studies/control_study.hpp).
// Its own options, and the other kinds' options refused for it (and its options for them).
#include <array>
#include <string_view>

#include "command.hpp"
#include "options.hpp"

namespace rodlab::cli {

/// The options only `study control` takes (listed in `rodlab study --help`).
inline constexpr std::array<OptionSpec, 8> kStudyControlOptions{
    OptionSpec{"--controllers", "A,B,...",
               "control: Table 4.1's columns, nlsq-implicit (one per --dt-control), "
               "nlsq-kirchhoff (variational plant, implicit-midpoint model), lqr, ilqr (default: "
               "these four); nlsq-kirchhoff-variational (the thesis': variational also as the "
               "model, slow)"},
    OptionSpec{"--horizons", "H1,H2,...",
               "control: horizons, integers >= 1 (default 1,2,5,10,15,20; lqr has none)"},
    OptionSpec{"--dt-control", "X1,X2,...",
               "control: the nlsq-implicit columns' control steps [s] > 0 (default 0.01,0.05,0.1; "
               "the other columns: 0.05)"},
    OptionSpec{"--tasks", "T1,T2,...", "control: reach, hold, track (default: all three)"},
    OptionSpec{"--targets", "K", "control: targets per reach and hold run, integer >= 1 (default 10)"},
    OptionSpec{"--seed", "K", "control: seed of the drawn targets, integer >= 0 (default 1)"},
    OptionSpec{"--max-wall-time", "S",
               "control: stop a run after S s, > 0 (recorded as timed out; default: no limit)"},
    OptionSpec{"--no-figures", "", "control: do not run validation/make_figures.py"}};

/// The options of the other study kinds that `study control` refuses.
inline constexpr std::array<std::string_view, 10> kOptionsNotForControl{
    "--schemes", "--dt", "--t-end", "--refine", "--reference",
    "--tol",     "--budget-ms", "--repeats", "--moduli", "--jobs"};

/// Runs `rodlab study control` (everything checked before anything runs or is written).
int run_control_study_kind(const Invocation& inv);

}  // namespace rodlab::cli
