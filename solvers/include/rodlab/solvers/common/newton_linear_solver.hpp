#pragma once
// The linear solver of the Newton systems in KinsolSolver and IdaSolver.

namespace rodlab::solvers {

/// `klu`: KLU on the whole sparse Newton matrix.
/// `condensed_rod_blocks`: for the semi-discrete rod's Newton matrix a I - df/dy (block
/// tridiagonal in nodes of 13 unknowns p, q, eta whose 7 pose rows involve their own node alone,
/// semi_discrete_rod.hpp), optionally bordered by rows that depend on every node and that no
/// row depends on (`ida`'s ledger rows): the pose rows are condensed node by node, the 6 x 6
/// block-tridiagonal Schur system is solved by block LU and the border by forward substitution
/// (condensed_block_lu.hpp); KLU factorises a matrix whose values break that structure or whose
/// pivot blocks look ill-conditioned. The same solutions to rounding, at a fraction of KLU's cost
/// (docs/dynamics.md "implicit-midpoint-collocation", "ida").
/// `almost_block_diagonal`: for a two-point boundary-value problem's Jacobian in blocks of 13
/// unknowns, 7 rows on the first block, 13 rows on each pair of neighbouring blocks and 6 on the
/// last, optionally bordered by up to 32 dense rows and columns (kinsol statics and its extra
/// unknowns): partial pivoting panel by panel, the factors of dense partial pivoting at a
/// fraction of KLU's cost, and the border by block LU on them (KLU factorises a bordered matrix
/// whose pivots look ill-conditioned; almost_block_diagonal_lu.hpp, docs/statics.md "Cost").
/// It factorises at every setup; KluReuse and KluOrder are those of its KLU fallback, and
/// KluReuse::factors keeps its own factors across KINSol calls too.
enum class NewtonLinearSolver { klu, condensed_rod_blocks, almost_block_diagonal };

}  // namespace rodlab::solvers
