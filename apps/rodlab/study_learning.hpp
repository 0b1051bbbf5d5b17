#pragma once
// `rodlab study learning SCENE` (docs/learning.md "Study"): its options and runner.
#include <array>

#include "command.hpp"
#include "options.hpp"

namespace rodlab::cli {

inline constexpr std::array<OptionSpec, 3> kStudyLearningOptions{
    OptionSpec{"--algorithms", "A,B", "learning: ddpg, gps (default: both)"},
    OptionSpec{"--seeds", "K", "learning: train with seeds 1..K, integer >= 1 (default 5)"},
    OptionSpec{"--budget-scale", "X",
               "learning: multiply every task's sample budget by X > 0 (default 1)"}};

int run_learning_study_kind(const Invocation& inv);

}  // namespace rodlab::cli
