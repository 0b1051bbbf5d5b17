#pragma once
// Turns node values (s, g, Lambda) of any statics scheme into the common result type, with the
// structure diagnostics (det and orthogonality of every R) computed the same way for all.
#include <span>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/statics/static_problem.hpp"

namespace rodlab::solvers::statics {

/// Fills centreline, base_wrench and diagnostics; the caller sets the solver fields.
void fill_static_result(const StaticProblem& problem, std::span<const double> s,
                        std::span<const SE3> g, std::span<const Vector6> Lambda,
                        result::StaticResult& out);

}  // namespace rodlab::solvers::statics
