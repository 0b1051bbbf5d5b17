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

/// A displacement-controlled cable whose converged tension is negative would have to push: it
/// goes slack instead, which the model does not represent. Marks such a result as not converged
/// with the reason ("... goes slack"); the problem holds the solution's extra unknowns.
void check_cables_taut(const StaticProblem& problem, result::StaticResult& out);

}  // namespace rodlab::solvers::statics
